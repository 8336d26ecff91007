// glTF materials → rtpbr_gltf_material (the table in docs/materials.md) and
// texture decoding (scene_image_decode.cpp).
#include "scene_image_decode.hpp"
#include "scene_internal.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

namespace rtpbr_gltf_detail {

namespace {

struct MaterialReader {
    Context& ctx;
    int material_index;
    const char* block;  // name of the JSON object being read, for messages

    bool number(const tinygltf::Value& obj, const char* key, double def, double* out) {
        *out = def;
        if (!obj.IsObject() || !obj.Has(key)) return true;
        const tinygltf::Value& v = obj.Get(key);
        if (!v.IsNumber())
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: %s.%s must be a number",
                            material_index, block, key);
        *out = v.GetNumberAsDouble();
        if (!fits_float(*out))
            return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "material %d: %s.%s is not finite",
                            material_index, block, key);
        return true;
    }

    // Reads an array of n (or, if n_alt > 0, n_alt) finite numbers.
    bool vector(const tinygltf::Value& obj, const char* key, size_t n, size_t n_alt, float* out,
                bool* present) {
        *present = false;
        if (!obj.IsObject() || !obj.Has(key)) return true;
        const tinygltf::Value& v = obj.Get(key);
        if (!v.IsArray() || (v.ArrayLen() != n && v.ArrayLen() != n_alt))
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON,
                            "material %d: %s.%s must be an array of %zu numbers", material_index,
                            block, key, n);
        for (size_t i = 0; i < v.ArrayLen(); ++i) {
            const tinygltf::Value& e = v.Get(static_cast<int>(i));
            if (!e.IsNumber())
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON,
                                "material %d: %s.%s[%zu] must be a number", material_index, block,
                                key, i);
            double d = e.GetNumberAsDouble();
            if (!fits_float(d))
                return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "material %d: %s.%s[%zu] is not finite",
                                material_index, block, key, i);
            out[i] = static_cast<float>(d);
        }
        *present = true;
        return true;
    }
};

bool finite_vector(Context& ctx, const std::vector<double>& v, size_t n, int material,
                   const char* name, float* out) {
    if (v.size() != n)
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: %s has %zu components, expected %zu",
                        material, name, v.size(), n);
    for (size_t i = 0; i < n; ++i) {
        if (!fits_float(v[i]))
            return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "material %d: %s[%zu] is not finite",
                            material, name, i);
        out[i] = static_cast<float>(v[i]);
    }
    return true;
}

float clamp01(Context& ctx, float v, int material, const char* name) {
    if (v < 0.0f || v > 1.0f) {
        ctx.warn("material %d: %s = %g clamped to [0,1]", material, name, static_cast<double>(v));
        v = std::min(1.0f, std::max(0.0f, v));
    }
    return v;
}

// Dielectric normal-incidence reflectance of an interface air → ior;
// ior = 0 is KHR_materials_ior's "F0 = 1". (Fresnel equations at θ = 0)
float f0_from_ior(float ior) {
    if (ior == 0.0f) return 1.0f;
    float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

const tinygltf::Value* find_extension(const tinygltf::ExtensionMap& map, const char* name) {
    auto it = map.find(name);
    return it == map.end() ? nullptr : &it->second;
}

// stb_image 2022-09-08 (Debian 12) builds a JPEG Huffman table of up to 16 x 255 codes into
// arrays of 257 entries: a DHT segment whose code counts sum past 256 writes out of bounds
// (found by fuzz_scene; upstream checks it since 2.28). Every DHT segment is checked here
// before stb_image sees the file, including those between the scans of a progressive JPEG,
// and read the way stb_image reads it: table after table while the segment length says more
// follow, each table's 17 header bytes read even past the segment's end (zeros past the end
// of the data). And it decodes a scan with whatever its Huffman table holds when no DHT
// segment defined that table (memory it never initialised: an index of 1e9 into a 257-entry
// array, found by fuzz_scene): each scan's components must name tables defined before it, the
// ones stb_image decodes that scan with (baseline: DC and AC; progressive: DC in a first DC
// scan, AC in an AC scan).
bool jpeg_huffman_tables_ok(const unsigned char* p, size_t size) {
    auto byte = [&](size_t i) -> unsigned { return i < size ? p[i] : 0u; };
    bool defined[2][4] = {};  // [class: 0 DC, 1 AC][index]
    bool progressive = false;
    size_t at = 2;  // after SOI
    while (at + 1 < size) {
        if (p[at] != 0xff) {  // entropy-coded data: skip to the next marker
            ++at;
            continue;
        }
        const unsigned marker = p[at + 1];
        if (marker == 0xff || marker == 0x00 || (marker >= 0xd0 && marker <= 0xd7) || marker == 0x01) {
            ++at;  // fill byte, stuffed 0xff, restart marker or TEM: no length follows
            continue;
        }
        if (marker == 0xd9) return true;  // EOI
        const long length = long(byte(at + 2) << 8 | byte(at + 3));
        if (marker == 0xc2) progressive = true;  // SOF2
        if (marker == 0xc4) {
            size_t t = at + 4;
            for (long left = length - 2; left > 0;) {
                unsigned codes = 0;
                for (size_t i = 1; i <= 16; ++i) codes += byte(t + i);
                if (codes > 256) return false;
                const unsigned cls = byte(t) >> 4, index = byte(t) & 15u;
                if (cls <= 1 && index <= 3) defined[cls][index] = true;  // else stb_image refuses it
                t += 17 + codes;
                left -= 17 + long(codes);
            }
        }
        if (marker == 0xda) {  // SOS: Ns, then (component, DC table << 4 | AC table) each, Ss, Se, Ah/Al
            const unsigned count = byte(at + 4);
            const size_t spectral = at + 5 + 2 * size_t(count);
            const unsigned ss = byte(spectral), se = byte(spectral + 1), ah = byte(spectral + 2) >> 4;
            const bool dc = !progressive || (ss == 0 && ah == 0), ac = !progressive || se > 0;
            for (unsigned c = 0; c < count; ++c) {
                const unsigned tables = byte(at + 6 + 2 * size_t(c)), d = tables >> 4, a = tables & 15u;
                if ((dc && d <= 3 && !defined[0][d]) || (ac && a <= 3 && !defined[1][a])) return false;
            }
        }
        if (length < 2) return true;  // stb_image stops at such a segment
        at += 2 + size_t(length);
    }
    return true;
}

struct TextureTable {
    Context& ctx;
    const tinygltf::Model& model;
    Scene& scene;
    std::map<std::pair<int, bool>, int32_t> made;  // (gltf texture, srgb) → output index
    std::map<int, std::pair<std::pair<uint32_t, uint32_t>, std::vector<uint8_t>>> decoded;

    bool encoded_bytes(int image_index, const unsigned char** bytes, size_t* size) {
        const tinygltf::Image& image = model.images[size_t(image_index)];
        if (image.bufferView >= 0) {
            if (size_t(image.bufferView) >= model.bufferViews.size())
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE,
                                "image %d: bufferView %d does not exist (%zu bufferViews)",
                                image_index, image.bufferView, model.bufferViews.size());
            const tinygltf::BufferView& view = model.bufferViews[size_t(image.bufferView)];
            if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size())
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE,
                                "bufferView %d: buffer %d does not exist", image.bufferView,
                                view.buffer);
            const size_t buffer_size = model.buffers[size_t(view.buffer)].data.size();
            if (view.byteOffset > buffer_size || view.byteLength > buffer_size - view.byteOffset)
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                                "image %d: bufferView %d (byteOffset %zu + byteLength %zu) exceeds "
                                "buffer %d (%zu bytes)",
                                image_index, image.bufferView, view.byteOffset, view.byteLength,
                                view.buffer, buffer_size);
            *bytes = model.buffers[size_t(view.buffer)].data.data() + view.byteOffset;
            *size = view.byteLength;
            return true;
        }
        auto it = ctx.encoded_images.find(image_index);
        if (it == ctx.encoded_images.end() || it->second.empty())
            return ctx.fail(RTPBR_GLTF_ERROR_FILE_NOT_FOUND, "image %d: '%s' could not be loaded",
                            image_index, image.uri.size() > 200 ? "(long uri)" : image.uri.c_str());
        *bytes = it->second.data();
        *size = it->second.size();
        return true;
    }

    // Checks that `bytes` more decoded texels fit in the budget (they are counted by the caller).
    bool reserve_texels(int image_index, uint64_t bytes, int w, int h) {
        if (bytes <= ctx.texture_budget && ctx.texture_bytes <= ctx.texture_budget - bytes) return true;
        return ctx.fail(RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE,
                        "image %d (%dx%d): %.1f MiB of decoded texels would exceed the texture memory budget of "
                        "%.1f MiB (%.1f MiB already used; desc.texture_memory_budget)",
                        image_index, w, h, double(bytes) / 1048576.0, double(ctx.texture_budget) / 1048576.0,
                        double(ctx.texture_bytes) / 1048576.0);
    }

    bool decode(int image_index) {
        if (decoded.count(image_index)) return true;
        auto& slot = decoded[image_index];
        if (ctx.desc.skip_images) return true;
        const unsigned char* bytes = nullptr;
        size_t size = 0;
        if (!encoded_bytes(image_index, &bytes, &size)) return false;
        if (size == 0 || size > size_t(std::numeric_limits<int>::max()))
            return ctx.fail(RTPBR_GLTF_ERROR_IMAGE_DECODE, "image %d: %zu bytes of encoded data",
                            image_index, size);
        // stb_image refuses PNGs above 2^30 bytes of pixels as "unknown image type": read
        // the IHDR size (PNG spec: signature, then IHDR width/height big-endian) to say why.
        static const unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
        if (size >= 24 && std::memcmp(bytes, kPngSignature, 8) == 0 && std::memcmp(bytes + 12, "IHDR", 4) == 0) {
            const auto be32 = [&](size_t at) {
                return uint32_t(bytes[at]) << 24 | uint32_t(bytes[at + 1]) << 16 | uint32_t(bytes[at + 2]) << 8 |
                       uint32_t(bytes[at + 3]);
            };
            const uint32_t pw = be32(16), ph = be32(20);
            if (pw > ctx.max_texture_dimension || ph > ctx.max_texture_dimension)
                return ctx.fail(RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE,
                                "image %d: %ux%u exceeds the maximum texture dimension %u", image_index, pw, ph,
                                ctx.max_texture_dimension);
        }
        // Only the formats glTF 2.0 allows (and our docs name) are decoded: stb_image would
        // also decode PNM, TGA, PSD, ... whose few-byte headers can claim 8000² pixels.
        static const unsigned char kJpegSoi[3] = {0xff, 0xd8, 0xff};
        const bool png = size >= 8 && std::memcmp(bytes, kPngSignature, 8) == 0;
        const bool jpeg = size >= 3 && std::memcmp(bytes, kJpegSoi, 3) == 0;
        if (!png && !jpeg)
            return ctx.fail(RTPBR_GLTF_ERROR_IMAGE_DECODE,
                            "image %d: neither PNG nor JPEG (first bytes %02x %02x %02x %02x); only these "
                            "are decoded",
                            image_index, bytes[0], size > 1 ? bytes[1] : 0, size > 2 ? bytes[2] : 0,
                            size > 3 ? bytes[3] : 0);
        if (jpeg && !jpeg_huffman_tables_ok(bytes, size))
            return ctx.fail(RTPBR_GLTF_ERROR_IMAGE_DECODE,
                            "image %d: corrupt JPEG (a Huffman table with more than 256 codes, or a scan using one "
                            "that was never defined)", image_index);
        ImageHeader header;
        const char* why = nullptr;
        if (!read_image_header(bytes, size, &header, &why))
            return ctx.fail(RTPBR_GLTF_ERROR_IMAGE_DECODE, "image %d: not a decodable PNG/JPEG image (%s)",
                            image_index, why);
        const int w = header.width, h = header.height;
        if (w <= 0 || h <= 0 || uint32_t(w) > ctx.max_texture_dimension ||
            uint32_t(h) > ctx.max_texture_dimension)
            return ctx.fail(RTPBR_GLTF_ERROR_TEXTURE_TOO_LARGE,
                            "image %d: %dx%d exceeds the maximum texture dimension %u", image_index,
                            w, h, ctx.max_texture_dimension);
        // The budget, from the header, before the decoder reserves anything; the decoder itself
        // is held to what such a header can need, so a stream that inflates past it stops there.
        const uint64_t bytes_per_texel = header.sixteen_bit ? 8 : 4;
        if (!reserve_texels(image_index, uint64_t(w) * uint64_t(h) * bytes_per_texel, w, h)) return false;
        const uint64_t limit = image_decode_memory_limit(header, size);
        DecodedImage image;
        switch (decode_image_rgba8(bytes, size, limit, &image)) {
        case ImageDecodeStatus::ok: break;
        case ImageDecodeStatus::over_memory_limit:
            return ctx.fail(RTPBR_GLTF_ERROR_IMAGE_DECODE,
                            "image %d (%dx%d): decoding took more than %.1f MiB, the most an image of that "
                            "size needs: its compressed data expands past what its header declares "
                            "(corrupt or hostile image)",
                            image_index, w, h, double(limit) / 1048576.0);
        case ImageDecodeStatus::corrupt:
            return ctx.fail(RTPBR_GLTF_ERROR_IMAGE_DECODE, "image %d: %s", image_index, image.why);
        }
        if (image.width != w || image.height != h)
            return ctx.fail(RTPBR_GLTF_ERROR_IMAGE_DECODE, "image %d: decoder returned %dx%d, the header says %dx%d",
                            image_index, image.width, image.height, w, h);
        slot.first = {uint32_t(w), uint32_t(h)};
        ctx.texture_bytes += image.rgba.size();  // what stays; a 16-bit intermediate is gone
        slot.second = std::move(image.rgba);
        return true;
    }

    static rtpbr_gltf_wrap wrap(int gl) {
        if (gl == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return RTPBR_GLTF_WRAP_CLAMP_TO_EDGE;
        if (gl == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return RTPBR_GLTF_WRAP_MIRRORED_REPEAT;
        return RTPBR_GLTF_WRAP_REPEAT;
    }

    static rtpbr_gltf_min_filter min_filter(int gl) {
        switch (gl) {
        case TINYGLTF_TEXTURE_FILTER_NEAREST: return RTPBR_GLTF_MIN_FILTER_NEAREST;
        case TINYGLTF_TEXTURE_FILTER_LINEAR: return RTPBR_GLTF_MIN_FILTER_LINEAR;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: return RTPBR_GLTF_MIN_FILTER_NEAREST_MIPMAP_NEAREST;
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: return RTPBR_GLTF_MIN_FILTER_LINEAR_MIPMAP_NEAREST;
        case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: return RTPBR_GLTF_MIN_FILTER_NEAREST_MIPMAP_LINEAR;
        case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: return RTPBR_GLTF_MIN_FILTER_LINEAR_MIPMAP_LINEAR;
        default: return RTPBR_GLTF_MIN_FILTER_DEFAULT;
        }
    }

    // KHR_texture_transform of one textureInfo (`ext`: the extension's object, or null) and the
    // texture coordinate set the slot reads (its texCoord, or the extension's override).
    bool transform(int material, const char* slot_name, int tex_coord, const tinygltf::Value* ext,
                   rtpbr_gltf_texture_transform* out) {
        *out = rtpbr_gltf_texture_transform{};
        out->scale[0] = out->scale[1] = 1.0f;
        if (ext) {
            if (!ext->IsObject())
                return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: %s.extensions.KHR_texture_transform must be an object",
                                material, slot_name);
            std::string block = std::string(slot_name) + ".KHR_texture_transform";
            MaterialReader r{ctx, material, block.c_str()};
            bool present;
            double d;
            if (!r.vector(*ext, "offset", 2, 0, out->offset, &present) ||
                !r.vector(*ext, "scale", 2, 0, out->scale, &present) || !r.number(*ext, "rotation", 0.0, &d))
                return false;
            out->rotation = float(d);
            if (ext->Has("texCoord")) {
                const tinygltf::Value& tc = ext->Get("texCoord");
                if (!tc.IsNumber() || tc.GetNumberAsDouble() < 0.0 || tc.GetNumberAsDouble() > 2147483647.0 ||
                    tc.GetNumberAsDouble() != std::floor(tc.GetNumberAsDouble()))
                    return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: %s.texCoord must be an integer >= 0",
                                    material, block.c_str());
                tex_coord = int(tc.GetNumberAsDouble());
            }
            out->has_transform = true;
        }
        if (tex_coord > 1) {
            ctx.warn("material %d: %s uses TEXCOORD_%d; only TEXCOORD_0 and TEXCOORD_1 are read (TEXCOORD_0 used)",
                     material, slot_name, tex_coord);
            tex_coord = 0;
        }
        out->texcoord = uint32_t(tex_coord);
        return true;
    }

    // Returns false on failure; *out = -1 when the texture is unusable. `ext_transform` is the
    // textureInfo's KHR_texture_transform object or null.
    bool get(int material, const char* slot_name, const tinygltf::Value* ext_transform, int texture_index,
             int tex_coord, bool srgb, int32_t* out, rtpbr_gltf_texture_transform* out_transform) {
        *out = -1;
        if (!transform(material, slot_name, texture_index < 0 ? 0 : tex_coord, ext_transform, out_transform))
            return false;
        if (texture_index < 0) return true;
        if (size_t(texture_index) >= model.textures.size())
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE,
                            "material %d: %s.index %d does not exist (%zu textures)", material,
                            slot_name, texture_index, model.textures.size());
        auto key = std::make_pair(texture_index, srgb);
        auto it = made.find(key);
        if (it != made.end()) {
            *out = it->second;
            return true;
        }
        const tinygltf::Texture& tex = model.textures[size_t(texture_index)];
        if (tex.source < 0) {
            ctx.warn("texture %d has no source image; ignored", texture_index);
            return true;
        }
        if (size_t(tex.source) >= model.images.size())
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE,
                            "texture %d: source image %d does not exist (%zu images)", texture_index,
                            tex.source, model.images.size());
        if (tex.sampler >= 0 && size_t(tex.sampler) >= model.samplers.size())
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE,
                            "texture %d: sampler %d does not exist (%zu samplers)", texture_index,
                            tex.sampler, model.samplers.size());
        if (!decode(tex.source)) return false;
        Texture t;
        const auto& d = decoded[tex.source];
        // Each texture holds its own copy of the image's texels.
        const uint64_t copy_bytes = uint64_t(d.first.first) * d.first.second * 4;
        if (!reserve_texels(tex.source, copy_bytes, int(d.first.first), int(d.first.second))) return false;
        ctx.texture_bytes += copy_bytes;
        t.width = d.first.first;
        t.height = d.first.second;
        t.pixels = d.second;
        t.info.width = t.width;
        t.info.height = t.height;
        t.info.srgb = srgb;
        t.info.gltf_texture = texture_index;
        if (tex.sampler >= 0) {
            const tinygltf::Sampler& s = model.samplers[size_t(tex.sampler)];
            t.info.wrap_s = wrap(s.wrapS);
            t.info.wrap_t = wrap(s.wrapT);
            t.info.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
            t.info.min_filter = min_filter(s.minFilter);
        }
        scene.textures.push_back(std::move(t));
        *out = int32_t(scene.textures.size() - 1);
        made[key] = *out;
        return true;
    }
};

// A textureInfo inside a material extension's JSON (tinygltf leaves those as plain values):
// index, texCoord, the normal textures' scale, and its KHR_texture_transform.
bool extension_texture(Context& ctx, TextureTable& textures, int material, const tinygltf::Value& ext,
                       const char* extension, const char* key, bool srgb, int32_t* out,
                       rtpbr_gltf_texture_transform* out_transform, float* out_scale = nullptr) {
    *out = -1;
    const std::string slot = std::string(extension) + "." + key;
    if (!ext.IsObject() || !ext.Has(key))
        return textures.get(material, slot.c_str(), nullptr, -1, 0, srgb, out, out_transform);
    const tinygltf::Value& info = ext.Get(key);
    auto integer = [&](const char* name, int* v) {
        if (!info.Has(name)) return true;
        const tinygltf::Value& x = info.Get(name);
        const double d = x.IsNumber() ? x.GetNumberAsDouble() : -1.0;
        if (!(d >= 0.0 && d <= 2147483647.0 && d == std::floor(d)))
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: %s.%s must be an integer >= 0", material,
                            slot.c_str(), name);
        *v = int(d);
        return true;
    };
    int texture = -1, tex_coord = 0;
    if (!info.IsObject() || !info.Has("index"))
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: %s must be an object with an index", material,
                        slot.c_str());
    if (!integer("index", &texture) || !integer("texCoord", &tex_coord)) return false;
    if (out_scale) {
        MaterialReader r{ctx, material, slot.c_str()};
        double d;
        if (!r.number(info, "scale", 1.0, &d)) return false;
        *out_scale = float(d);
    }
    const tinygltf::Value* transform = nullptr;
    if (info.Has("extensions") && info.Get("extensions").IsObject() &&
        info.Get("extensions").Has("KHR_texture_transform"))
        transform = &info.Get("extensions").Get("KHR_texture_transform");
    return textures.get(material, slot.c_str(), transform, texture, tex_coord, srgb, out, out_transform);
}

// The material being read and what its readers share: each reader below fills the part of m
// its glTF object or extension names, and fails (ctx.fail) or warns as the loader does.
struct MaterialInput {
    Context& ctx;
    TextureTable& textures;
    int index;  // the glTF material
    rtpbr_gltf_material& m;

    // A textureInfo inside one of the material's extensions (extension_texture).
    bool texture(const tinygltf::Value& ext, const char* extension, const char* key, bool srgb, int32_t* out,
                 rtpbr_gltf_texture_transform* transform, float* scale = nullptr) {
        return extension_texture(ctx, textures, index, ext, extension, key, srgb, out, transform, scale);
    }
    // A factor documented in [0,1]: read (default def), then clamped with a warning.
    bool factor01(MaterialReader& r, const tinygltf::Value& obj, const char* key, double def, float* out) {
        double d;
        if (!r.number(obj, key, def, &d)) return false;
        *out = clamp01(ctx, float(d), index, key);
        return true;
    }
};

// Core metallic-roughness factors, alpha and sidedness; emissiveFactor into emissive (the
// emission waits for KHR_materials_emissive_strength).
bool read_core(MaterialInput& in, const tinygltf::Material& src, float emissive[3]) {
    Context& ctx = in.ctx;
    rtpbr_gltf_material& m = in.m;
    const int index = in.index;
    const auto& pbr = src.pbrMetallicRoughness;
    if (!finite_vector(ctx, pbr.baseColorFactor, 4, index, "baseColorFactor", m.base_color))
        return false;
    for (int k = 0; k < 4; ++k) m.base_color[k] = clamp01(ctx, m.base_color[k], index, "baseColorFactor");
    if (!fits_float(pbr.metallicFactor) || !fits_float(pbr.roughnessFactor))
        return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "material %d: metallic/roughnessFactor not finite", index);
    m.metallic = clamp01(ctx, float(pbr.metallicFactor), index, "metallicFactor");
    m.roughness = clamp01(ctx, float(pbr.roughnessFactor), index, "roughnessFactor");
    if (!finite_vector(ctx, src.emissiveFactor, 3, index, "emissiveFactor", emissive)) return false;
    for (int k = 0; k < 3; ++k) emissive[k] = clamp01(ctx, emissive[k], index, "emissiveFactor");
    m.double_sided = src.doubleSided;
    if (src.alphaMode == "MASK") m.alpha_mode = RTPBR_GLTF_ALPHA_MASK;
    else if (src.alphaMode == "BLEND") m.alpha_mode = RTPBR_GLTF_ALPHA_BLEND;
    else if (src.alphaMode != "OPAQUE" && !src.alphaMode.empty())
        ctx.warn("material %d: unknown alphaMode '%s' treated as OPAQUE", index, src.alphaMode.c_str());
    if (!fits_float(src.alphaCutoff) || !fits_float(src.normalTexture.scale))
        return ctx.fail(RTPBR_GLTF_ERROR_NONFINITE, "material %d: alphaCutoff/normalTexture.scale not finite", index);
    m.alpha_cutoff = float(src.alphaCutoff);
    m.normal_scale = float(src.normalTexture.scale);
    return true;
}

// The core textures (base colour, metallic-roughness, normal, emissive), each with its
// KHR_texture_transform.
bool read_core_textures(MaterialInput& in, const tinygltf::Material& src) {
    rtpbr_gltf_material& m = in.m;
    const int index = in.index;
    const auto& pbr = src.pbrMetallicRoughness;
    auto transform_of = [](const tinygltf::ExtensionMap& extensions) {
        return find_extension(extensions, "KHR_texture_transform");
    };
    if (!in.textures.get(index, "baseColorTexture", transform_of(pbr.baseColorTexture.extensions),
                         pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, true, &m.base_color_texture,
                         &m.base_color_texture_transform) ||
        !in.textures.get(index, "metallicRoughnessTexture", transform_of(pbr.metallicRoughnessTexture.extensions),
                         pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, false,
                         &m.metallic_roughness_texture, &m.metallic_roughness_texture_transform) ||
        !in.textures.get(index, "normalTexture", transform_of(src.normalTexture.extensions),
                         src.normalTexture.index, src.normalTexture.texCoord, false, &m.normal_texture,
                         &m.normal_texture_transform) ||
        !in.textures.get(index, "emissiveTexture", transform_of(src.emissiveTexture.extensions),
                         src.emissiveTexture.index, src.emissiveTexture.texCoord, true, &m.emission_texture,
                         &m.emission_texture_transform))
        return false;
    if (src.occlusionTexture.index >= 0)
        in.ctx.warn("material %d: occlusionTexture ignored", index);
    return true;
}

bool read_emissive_strength(MaterialInput& in, const tinygltf::Value& ext) {
    MaterialReader r{in.ctx, in.index, "KHR_materials_emissive_strength"};
    double d;
    if (!r.number(ext, "emissiveStrength", 1.0, &d)) return false;
    if (d < 0.0)
        return in.ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: emissiveStrength %g < 0", in.index, d);
    in.m.emissive_strength.emissive_strength = float(d);
    in.m.has_emissive_strength = true;
    return true;
}

bool read_ior(MaterialInput& in, const tinygltf::Value& ext) {
    MaterialReader r{in.ctx, in.index, "KHR_materials_ior"};
    double d;
    if (!r.number(ext, "ior", 1.5, &d)) return false;
    if (!(d == 0.0 || d >= 1.0))
        return in.ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON,
                           "material %d: KHR_materials_ior.ior %g is neither 0 nor >= 1", in.index, d);
    in.m.ior.ior = float(d);
    in.m.has_ior = true;
    return true;
}

bool read_specular(MaterialInput& in, const tinygltf::Value& ext) {
    static const char* const name = "KHR_materials_specular";
    MaterialReader r{in.ctx, in.index, name};
    rtpbr_gltf_specular& s = in.m.specular;
    bool present;
    if (!in.factor01(r, ext, "specularFactor", 1.0, &s.specular_factor)) return false;
    if (!r.vector(ext, "specularColorFactor", 3, 0, s.specular_color_factor, &present)) return false;
    for (int k = 0; k < 3; ++k)
        if (s.specular_color_factor[k] < 0.0f)
            return in.ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: specularColorFactor < 0", in.index);
    if (!in.texture(ext, name, "specularTexture", false, &s.specular_texture, &s.specular_texture_transform) ||
        !in.texture(ext, name, "specularColorTexture", true, &s.specular_color_texture,
                    &s.specular_color_texture_transform))
        return false;
    in.m.has_specular = true;
    return true;
}

bool read_clearcoat(MaterialInput& in, const tinygltf::Value& ext) {
    static const char* const name = "KHR_materials_clearcoat";
    MaterialReader r{in.ctx, in.index, name};
    rtpbr_gltf_clearcoat& c = in.m.clearcoat;
    if (!in.factor01(r, ext, "clearcoatFactor", 0.0, &c.clearcoat_factor) ||
        !in.factor01(r, ext, "clearcoatRoughnessFactor", 0.0, &c.clearcoat_roughness_factor))
        return false;
    if (!in.texture(ext, name, "clearcoatTexture", false, &c.clearcoat_texture, &c.clearcoat_texture_transform) ||
        !in.texture(ext, name, "clearcoatRoughnessTexture", false, &c.clearcoat_roughness_texture,
                    &c.clearcoat_roughness_texture_transform) ||
        !in.texture(ext, name, "clearcoatNormalTexture", false, &c.clearcoat_normal_texture,
                    &c.clearcoat_normal_texture_transform, &c.clearcoat_normal_scale))
        return false;
    if (c.clearcoat_normal_texture >= 0)
        in.ctx.warn("material %d: clearcoatNormalTexture ignored (the coat uses the base normal)", in.index);
    in.m.has_clearcoat = true;
    return true;
}

bool read_sheen(MaterialInput& in, const tinygltf::Value& ext) {
    static const char* const name = "KHR_materials_sheen";
    MaterialReader r{in.ctx, in.index, name};
    rtpbr_gltf_sheen& s = in.m.sheen;
    bool present;
    if (!r.vector(ext, "sheenColorFactor", 3, 0, s.sheen_color_factor, &present)) return false;
    for (int k = 0; k < 3; ++k)
        s.sheen_color_factor[k] = clamp01(in.ctx, s.sheen_color_factor[k], in.index, "sheenColorFactor");
    if (!in.factor01(r, ext, "sheenRoughnessFactor", 0.0, &s.sheen_roughness_factor)) return false;
    if (!in.texture(ext, name, "sheenColorTexture", true, &s.sheen_color_texture,
                    &s.sheen_color_texture_transform) ||
        !in.texture(ext, name, "sheenRoughnessTexture", false, &s.sheen_roughness_texture,
                    &s.sheen_roughness_texture_transform))
        return false;
    in.m.has_sheen = true;
    return true;
}

bool read_anisotropy(MaterialInput& in, const tinygltf::Value& ext) {
    MaterialReader r{in.ctx, in.index, "KHR_materials_anisotropy"};
    double d;
    if (!in.factor01(r, ext, "anisotropyStrength", 0.0, &in.m.anisotropy.anisotropy_strength) ||
        !r.number(ext, "anisotropyRotation", 0.0, &d))
        return false;
    in.m.anisotropy.anisotropy_rotation = float(d);
    if (ext.IsObject() && ext.Has("anisotropyTexture"))
        in.ctx.warn("material %d: KHR_materials_anisotropy.anisotropyTexture ignored", in.index);
    in.m.has_anisotropy = true;
    return true;
}

// The material extensions the loader reads, in reading order (KHR_materials_specular before
// extras.rtpbr_disney, whose default specular depends on it); other KHR_materials_* are
// ignored with a warning.
struct ExtensionReader {
    const char* name;
    bool (*read)(MaterialInput& in, const tinygltf::Value& ext);
};
const ExtensionReader kMaterialExtensions[] = {
    {"KHR_materials_emissive_strength", read_emissive_strength},
    {"KHR_materials_ior", read_ior},
    {"KHR_materials_specular", read_specular},
    {"KHR_materials_clearcoat", read_clearcoat},
    {"KHR_materials_sheen", read_sheen},
    {"KHR_materials_anisotropy", read_anisotropy},
};

void warn_unsupported_extensions(MaterialInput& in, const tinygltf::ExtensionMap& extensions) {
    for (const auto& e : extensions) {
        if (e.first.rfind("KHR_materials_", 0) != 0) continue;
        bool known = false;
        for (const ExtensionReader& x : kMaterialExtensions) known = known || e.first == x.name;
        if (!known) in.ctx.warn("material %d: extension %s ignored", in.index, e.first.c_str());
    }
}

// Disney parameters from extras.rtpbr_disney (Burley 2012 names).
bool read_disney(MaterialInput& in, const tinygltf::Value& dis) {
    Context& ctx = in.ctx;
    rtpbr_gltf_material& m = in.m;
    const int index = in.index;
    if (!dis.IsObject())
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: extras.rtpbr_disney must be an object", index);
    m.has_disney = true;
    MaterialReader r{ctx, index, "extras.rtpbr_disney"};
    rtpbr_gltf_disney& dn = m.disney;
    double d;
    bool present;
    struct Field { const char* key; float* dst; };
    const Field fields[] = {
        {"metallic", &m.metallic},          {"roughness", &m.roughness},
        {"subsurface", &dn.subsurface},     {"specular", &dn.specular},
        {"specularTint", &dn.specular_tint}, {"anisotropic", &dn.anisotropic},
        {"sheen", &dn.sheen},               {"sheenTint", &dn.sheen_tint},
        {"clearcoat", &dn.clearcoat},       {"clearcoatGloss", &dn.clearcoat_gloss},
    };
    for (const Field& f : fields)
        if (dis.Has(f.key) && !in.factor01(r, dis, f.key, 0.0, f.dst)) return false;
    float color[4] = {m.base_color[0], m.base_color[1], m.base_color[2], m.base_color[3]};
    if (!r.vector(dis, "baseColor", 3, 4, color, &present)) return false;
    for (int k = 0; k < 4; ++k) m.base_color[k] = clamp01(ctx, color[k], index, "baseColor");
    // Burley's specular from an IOR when the file gives none: F0(ior) x specularFactor / 0.08.
    float ior = m.ior.ior;
    if (dis.Has("ior")) {
        if (!r.number(dis, "ior", 1.5, &d)) return false;
        if (d < 1.0)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "material %d: extras.rtpbr_disney.ior %g < 1", index, d);
        ior = float(d);
    }
    if (!dis.Has("specular"))
        dn.specular = std::min(1.0f, f0_from_ior(ior) * m.specular.specular_factor / 0.08f);
    static const char* const known[] = {"metallic", "roughness", "subsurface", "specular",
                                        "specularTint", "anisotropic", "sheen", "sheenTint",
                                        "clearcoat", "clearcoatGloss", "baseColor", "ior"};
    for (const std::string& key : dis.Keys()) {
        bool ok = false;
        for (const char* k : known) ok = ok || key == k;
        if (!ok) ctx.warn("material %d: extras.rtpbr_disney.%s unknown, ignored", index, key.c_str());
    }
    return true;
}

// One glTF material: the core, each supported extension (kMaterialExtensions), the Disney extras.
bool convert_material(Context& ctx, const tinygltf::Model& model, int index, TextureTable& textures,
                      rtpbr_gltf_material* out) {
    const tinygltf::Material& src = model.materials[size_t(index)];
    rtpbr_gltf_material m = make_default_material();
    m.gltf_material = index;
    MaterialInput in{ctx, textures, index, m};
    float emissive[3];
    if (!read_core(in, src, emissive) || !read_core_textures(in, src)) return false;
    for (const ExtensionReader& x : kMaterialExtensions) {
        const tinygltf::Value* ext = find_extension(src.extensions, x.name);
        if (ext && !x.read(in, *ext)) return false;
    }
    warn_unsupported_extensions(in, src.extensions);
    for (int k = 0; k < 3; ++k) m.emission[k] = emissive[k] * m.emissive_strength.emissive_strength;
    if (src.extras.IsObject() && src.extras.Has("rtpbr_disney") && !read_disney(in, src.extras.Get("rtpbr_disney")))
        return false;
    *out = m;
    return true;
}

}  // namespace

rtpbr_gltf_material make_default_material() {
    // glTF 2.0 §3.9.6 default material: metallic = roughness = 1, white.
    rtpbr_gltf_material m;
    std::memset(&m, 0, sizeof m);
    for (int k = 0; k < 4; ++k) m.base_color[k] = 1.0f;
    m.metallic = 1.0f;
    m.roughness = 1.0f;
    // The extensions' defaults (their has_ flags stay false).
    m.ior.ior = 1.5f;
    m.specular.specular_factor = 1.0f;
    for (int k = 0; k < 3; ++k) m.specular.specular_color_factor[k] = 1.0f;
    m.emissive_strength.emissive_strength = 1.0f;
    // Burley's defaults (BRDF Explorer's disney.brdf): specular 0.5 (F0 0.04), gloss 1.
    m.disney.specular = 0.5f;
    m.disney.clearcoat_gloss = 1.0f;
    m.normal_scale = 1.0f;
    m.alpha_cutoff = 0.5f;
    m.alpha_mode = RTPBR_GLTF_ALPHA_OPAQUE;
    m.base_color_texture = m.metallic_roughness_texture = m.normal_texture = m.emission_texture = -1;
    m.specular.specular_texture = m.specular.specular_color_texture = -1;
    m.clearcoat.clearcoat_texture = m.clearcoat.clearcoat_roughness_texture = m.clearcoat.clearcoat_normal_texture = -1;
    m.clearcoat.clearcoat_normal_scale = 1.0f;
    m.sheen.sheen_color_texture = m.sheen.sheen_roughness_texture = -1;
    rtpbr_gltf_texture_transform* transforms[] = {
        &m.base_color_texture_transform, &m.metallic_roughness_texture_transform, &m.normal_texture_transform,
        &m.emission_texture_transform, &m.specular.specular_texture_transform,
        &m.specular.specular_color_texture_transform, &m.clearcoat.clearcoat_texture_transform,
        &m.clearcoat.clearcoat_roughness_texture_transform, &m.clearcoat.clearcoat_normal_texture_transform,
        &m.sheen.sheen_color_texture_transform, &m.sheen.sheen_roughness_texture_transform};
    for (rtpbr_gltf_texture_transform* t : transforms) t->scale[0] = t->scale[1] = 1.0f;
    m.gltf_material = -1;
    return m;
}

uint32_t default_material(Scene& scene) {
    for (uint32_t i = 0; i < scene.materials.size(); ++i)
        if (scene.materials[i].gltf_material == -1) return i;
    scene.materials.push_back(make_default_material());
    return uint32_t(scene.materials.size() - 1);
}

bool convert_materials(Context& ctx, const tinygltf::Model& model, Scene& scene) {
    TextureTable textures{ctx, model, scene, {}, {}};
    scene.materials.resize(model.materials.size());
    for (size_t i = 0; i < model.materials.size(); ++i)
        if (!convert_material(ctx, model, int(i), textures, &scene.materials[i])) return false;
    return true;
}

}  // namespace rtpbr_gltf_detail
