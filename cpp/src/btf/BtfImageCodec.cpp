// JPEG and PNG codecs over memory buffers.
//
// libjpeg reports fatal errors through error_exit, which here longjmps back. As in the PNG file
// code (core/Image.cpp), every libjpeg call that can fail runs inside a small guarded function
// whose frame owns no C++ object; buffers it fills belong to the caller, so a longjmp skips no
// destructor. PNG decoding lives in BtfPngDecode.cpp; PNG encoding uses libpng's simplified
// memory API, which reports errors by return value.
#include "btf/BtfImageCodec.h"

#include <weft/Error.h>

#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <jpeglib.h>
#include <png.h>

namespace weft {

namespace {

struct JpegError {
    jpeg_error_mgr mgr;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX] = "unknown libjpeg error";
};

void onJpegError(j_common_ptr cinfo) {
    auto* err = reinterpret_cast<JpegError*>(cinfo->err);
    (*cinfo->err->format_message)(cinfo, err->message);
    std::longjmp(err->jump, 1);
}

void onJpegMessage(j_common_ptr) {}

struct JpegDecoder {
    jpeg_decompress_struct info;
    JpegError error;
    JpegDecoder() {
        info.err = jpeg_std_error(&error.mgr);
        error.mgr.error_exit = onJpegError;
        error.mgr.output_message = onJpegMessage;
        jpeg_create_decompress(&info);
    }
    ~JpegDecoder() { jpeg_destroy_decompress(&info); }
    JpegDecoder(const JpegDecoder&) = delete;
    JpegDecoder& operator=(const JpegDecoder&) = delete;
};

bool jpegReadHeader(JpegDecoder& d, const uint8_t* data, size_t size) {
    if (setjmp(d.error.jump)) return false;
    jpeg_mem_src(&d.info, data, static_cast<unsigned long>(size));
    jpeg_read_header(&d.info, TRUE);
    if (d.info.num_components != 1) d.info.out_color_space = JCS_RGB;
    jpeg_start_decompress(&d.info);
    return true;
}

bool jpegReadRows(JpegDecoder& d, uint8_t* pixels, size_t rowBytes) {
    if (setjmp(d.error.jump)) return false;
    while (d.info.output_scanline < d.info.output_height) {
        JSAMPROW row = pixels + size_t(d.info.output_scanline) * rowBytes;
        jpeg_read_scanlines(&d.info, &row, 1);
    }
    jpeg_finish_decompress(&d.info);
    return true;
}

DecodedImage decodeJpeg(const std::vector<uint8_t>& bytes, const std::string& name) {
    JpegDecoder d;
    if (!jpegReadHeader(d, bytes.data(), bytes.size()))
        throw IoError("cannot read JPEG '" + name + "' (corrupt): " + d.error.message);
    DecodedImage img;
    img.width = int(d.info.output_width);
    img.height = int(d.info.output_height);
    img.channels = int(d.info.output_components);
    if (img.channels != 1 && img.channels != 3)
        throw IoError("JPEG '" + name + "' has an unsupported colour layout");
    if (img.width <= 0 || img.height <= 0 || img.width > 65536 || img.height > 65536)
        throw IoError("JPEG '" + name + "' has an impossible size");
    // JPEG compresses natural images at most a few hundred to one; refuse headers that claim far
    // more pixels than the data could hold before allocating.
    if (uint64_t(img.width) * uint64_t(img.height) > 4096ull * bytes.size() + (1u << 20))
        throw IoError("JPEG '" + name + "' claims a size impossible for its " +
                      std::to_string(bytes.size()) + " bytes (corrupt)");
    if (uint64_t(img.width) * uint64_t(img.height) * uint64_t(img.channels) > kMaxBtfImageBytes)
        throw IoError("JPEG '" + name + "' is " + std::to_string(img.width) + "x" +
                      std::to_string(img.height) + ", larger than a BTF image can be");
    const size_t rowBytes = size_t(img.width) * size_t(img.channels);
    img.pixels.resize(rowBytes * size_t(img.height));
    if (!jpegReadRows(d, img.pixels.data(), rowBytes))
        throw IoError("cannot read JPEG '" + name + "' (truncated or corrupt): " + d.error.message);
    if (d.error.mgr.num_warnings > 0)
        throw IoError("JPEG '" + name + "' is truncated or corrupt (libjpeg warnings)");
    return img;
}

bool jpegReadCoefficients(JpegDecoder& d, const uint8_t* data, size_t size,
                          jvirt_barray_ptr** arrays) {
    if (setjmp(d.error.jump)) return false;
    jpeg_mem_src(&d.info, data, static_cast<unsigned long>(size));
    jpeg_read_header(&d.info, TRUE);
    *arrays = jpeg_read_coefficients(&d.info);
    return true;
}

// Copies block rows out of libjpeg's virtual arrays; access_virt_barray can longjmp.
bool jpegCopyBlocks(JpegDecoder& d, jvirt_barray_ptr* arrays, int16_t* out) {
    if (setjmp(d.error.jump)) return false;
    for (int c = 0; c < d.info.num_components; ++c) {
        const jpeg_component_info& ci = d.info.comp_info[c];
        for (JDIMENSION row = 0; row < ci.height_in_blocks; ++row) {
            JBLOCKARRAY line = (*d.info.mem->access_virt_barray)(
                reinterpret_cast<j_common_ptr>(&d.info), arrays[c], row, 1, FALSE);
            for (JDIMENSION col = 0; col < ci.width_in_blocks; ++col, out += 64)
                for (int k = 0; k < 64; ++k) out[k] = int16_t(line[0][col][k]);
        }
    }
    jpeg_finish_decompress(&d.info);
    return true;
}

// The cells are only meaningful for grey or JFIF YCbCr baseline data whose blocks cover the
// decoded image; anything else returns no components.
JpegCoefficientImage readJpegCoefficients(const std::vector<uint8_t>& bytes,
                                          const std::string& name, int width, int height) {
    JpegDecoder d;
    jvirt_barray_ptr* arrays = nullptr;
    if (!jpegReadCoefficients(d, bytes.data(), bytes.size(), &arrays) || !arrays)
        throw IoError("cannot read JPEG '" + name + "' coefficients (corrupt): " + d.error.message);
    JpegCoefficientImage out;
    const bool grey = d.info.num_components == 1 && d.info.jpeg_color_space == JCS_GRAYSCALE;
    const bool ycc = d.info.num_components == 3 && d.info.jpeg_color_space == JCS_YCbCr;
    if ((!grey && !ycc) || int(d.info.image_width) != width || int(d.info.image_height) != height)
        return out;
    size_t blocks = 0;
    for (int c = 0; c < d.info.num_components; ++c) {
        const jpeg_component_info& ci = d.info.comp_info[c];
        if (!ci.quant_table) return JpegCoefficientImage{};
        JpegCoefficientImage::Component comp;
        comp.blocksWide = int(ci.width_in_blocks);
        comp.blocksHigh = int(ci.height_in_blocks);
        comp.hSampling = ci.h_samp_factor;
        comp.vSampling = ci.v_samp_factor;
        for (int k = 0; k < 64; ++k) comp.quant[k] = ci.quant_table->quantval[k];
        out.components.push_back(comp);
        blocks += size_t(comp.blocksWide) * size_t(comp.blocksHigh);
    }
    out.ycbcr = ycc;
    out.coefficients.resize(blocks * 64);
    if (!jpegCopyBlocks(d, arrays, out.coefficients.data()))
        throw IoError("cannot read JPEG '" + name +
                      "' coefficients (truncated or corrupt): " + d.error.message);
    return out;
}

struct JpegEncoder {
    jpeg_compress_struct info;
    JpegError error;
    unsigned char* buffer = nullptr;
    unsigned long size = 0;
    JpegEncoder() {
        info.err = jpeg_std_error(&error.mgr);
        error.mgr.error_exit = onJpegError;
        error.mgr.output_message = onJpegMessage;
        jpeg_create_compress(&info);
    }
    ~JpegEncoder() {
        jpeg_destroy_compress(&info);
        std::free(buffer);
    }
    JpegEncoder(const JpegEncoder&) = delete;
    JpegEncoder& operator=(const JpegEncoder&) = delete;
};

bool jpegWrite(JpegEncoder& e, const uint8_t* rgb, int width, int height, int quality) {
    if (setjmp(e.error.jump)) return false;
    jpeg_mem_dest(&e.info, &e.buffer, &e.size);
    e.info.image_width = JDIMENSION(width);
    e.info.image_height = JDIMENSION(height);
    e.info.input_components = 3;
    e.info.in_color_space = JCS_RGB;
    jpeg_set_defaults(&e.info);
    jpeg_set_quality(&e.info, quality, TRUE);
    jpeg_start_compress(&e.info, TRUE);
    while (e.info.next_scanline < e.info.image_height) {
        JSAMPROW row = const_cast<uint8_t*>(rgb) + size_t(e.info.next_scanline) * width * 3;
        jpeg_write_scanlines(&e.info, &row, 1);
    }
    jpeg_finish_compress(&e.info);
    return true;
}

} // namespace

DecodedImage decodeBtfImage(const std::vector<uint8_t>& bytes, const std::string& name,
                            bool jpegCoefficients) {
    static const uint8_t pngSig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) {
        DecodedImage img = decodeJpeg(bytes, name);
        if (jpegCoefficients)
            img.coefficients = readJpegCoefficients(bytes, name, img.width, img.height);
        return img;
    }
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), pngSig, 8) == 0)
        return decodePng(bytes, name);
    throw IoError("'" + name + "' is neither a JPEG nor a PNG (" + std::to_string(bytes.size()) +
                  " bytes)");
}

std::vector<uint8_t> encodeJpeg(const uint8_t* rgb, int width, int height, int quality) {
    if (quality < 1 || quality > 100) throw InvalidArgument("JPEG quality must be 1..100");
    JpegEncoder e;
    if (!jpegWrite(e, rgb, width, height, quality))
        throw IoError(std::string("JPEG encoding failed: ") + e.error.message);
    return std::vector<uint8_t>(e.buffer, e.buffer + e.size);
}

std::vector<uint8_t> encodePng(const uint8_t* rgb, int width, int height) {
    png_image image;
    std::memset(&image, 0, sizeof image);
    image.version = PNG_IMAGE_VERSION;
    image.width = png_uint_32(width);
    image.height = png_uint_32(height);
    image.format = PNG_FORMAT_RGB;
    png_alloc_size_t size = 0;
    if (!png_image_write_to_memory(&image, nullptr, &size, 0, rgb, 0, nullptr))
        throw IoError(std::string("PNG encoding failed: ") + image.message);
    std::vector<uint8_t> out(size);
    if (!png_image_write_to_memory(&image, out.data(), &size, 0, rgb, 0, nullptr))
        throw IoError(std::string("PNG encoding failed: ") + image.message);
    out.resize(size);
    return out;
}

} // namespace weft
