#pragma once
// Errors thrown by weft. Python sees weft.Error, weft.InvalidArgument (also a ValueError) and
// weft.IoError (also an OSError).
#include <stdexcept>
#include <string>

namespace weft {

/// Base class of every error weft throws.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A caller passed something impossible: wrong sizes, NaN/inf, out-of-range parameters.
class InvalidArgument : public Error {
public:
    using Error::Error;
};

/// A file is missing, unreadable, truncated or corrupt.
class IoError : public Error {
public:
    using Error::Error;
};

} // namespace weft
