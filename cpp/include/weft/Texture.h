#pragma once
// A texture is an immutable RGBA8 image plus how it is sampled; the renderer uploads it once.
#include <cstdint>
#include <memory>

#include <weft/Image.h>

namespace weft {

class Texture {
public:
    /// `image` is converted to RGBA. `srgb`: texel values are sRGB-encoded colour (decoded to
    /// linear when sampled); false for data such as normal maps. `mipmaps`: build a full chain.
    explicit Texture(ImageU8 image, bool srgb = true, bool mipmaps = true);

    const ImageU8& image() const { return mImage; }
    bool srgb() const { return mSrgb; }
    bool mipmaps() const { return mMipmaps; }
    /// Unique per texture object; the renderer caches GPU copies by it.
    uint64_t id() const { return mId; }

private:
    ImageU8 mImage;
    bool mSrgb;
    bool mMipmaps;
    uint64_t mId;
};

using TexturePtr = std::shared_ptr<const Texture>;

} // namespace weft
