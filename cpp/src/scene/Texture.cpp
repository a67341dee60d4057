#include <weft/Texture.h>

#include <atomic>

namespace weft {

namespace {
std::atomic<uint64_t> gNextTextureId{1};
}

Texture::Texture(ImageU8 image, bool srgb, bool mipmaps)
    : mSrgb(srgb), mMipmaps(mipmaps), mId(gNextTextureId++) {
    image.validate();
    mImage = image.channels == 4 ? std::move(image) : image.toRgba();
}

} // namespace weft
