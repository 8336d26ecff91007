// rtpbr oracle: bilinear texture lookups on the loader's RGBA8 textures.
#ifndef RTPBR_ORACLE_TEXTURE_H
#define RTPBR_ORACLE_TEXTURE_H

#include <rtpbr/rtpbr_gltf.h>

#include <glm/glm.hpp>

#include <cmath>
#include <vector>

namespace rtpbr_oracle {

// A texture slot's texture coordinates at a point whose TEXCOORD_0 and TEXCOORD_1 are uv0 and
// uv1: the slot's set through its KHR_texture_transform (rtpbr_gltf.h states the matrix).
inline glm::vec2 slotUv(const rtpbr_gltf_texture_transform &t, glm::vec2 uv0, glm::vec2 uv1) {
    glm::vec2 chosen = t.texcoord == 1 ? uv1 : uv0;
    float uv[2] = {chosen.x, chosen.y};
    rtpbr_gltf_texture_transform_apply(&t, uv); // the loader's one formula
    return glm::vec2(uv[0], uv[1]);
}

// Texels decoded to linear float once (sRGB textures through the sRGB EOTF), then sampled
// bilinearly (nearest when the texture asks for it) with the texture's wrap modes; no mipmaps:
// the oracle averages many samples per pixel, which filters the texture over the footprint.
class Texture {
public:
    explicit Texture(const rtpbr_gltf_texture &t) : w_(t.width), h_(t.height), wrapS_(t.wrap_s), wrapT_(t.wrap_t) {
        nearest_ = t.nearest;
        if (!t.pixels || w_ == 0 || h_ == 0) {
            w_ = h_ = 0;
            return;
        }
        texels_.resize(size_t(w_) * h_);
        for (size_t i = 0; i < texels_.size(); i++) {
            glm::vec4 c;
            for (int k = 0; k < 4; k++) {
                float v = float(t.pixels[4 * i + size_t(k)]) / 255.0f;
                // IEC 61966-2-1 sRGB transfer function (colour channels only).
                if (t.srgb && k < 3)
                    v = v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
                c[k] = v;
            }
            texels_[i] = c;
        }
    }

    // White when the texture has no pixels (skip_images), so factors pass through.
    glm::vec4 sample(float u, float v) const {
        if (w_ == 0)
            return glm::vec4(1.0f);
        if (!std::isfinite(u) || !std::isfinite(v) || std::fabs(u) > 1e6f || std::fabs(v) > 1e6f)
            u = v = 0.0f;
        float x = u * float(w_) - 0.5f;
        float y = v * float(h_) - 0.5f;
        if (nearest_)
            return texel(int(std::floor(x + 0.5f)), int(std::floor(y + 0.5f)));
        float fx = std::floor(x), fy = std::floor(y);
        float ax = x - fx, ay = y - fy;
        int ix = int(fx), iy = int(fy);
        return (1.0f - ay) * ((1.0f - ax) * texel(ix, iy) + ax * texel(ix + 1, iy)) +
               ay * ((1.0f - ax) * texel(ix, iy + 1) + ax * texel(ix + 1, iy + 1));
    }

private:
    static int wrap(int i, int n, rtpbr_gltf_wrap mode) {
        if (mode == RTPBR_GLTF_WRAP_CLAMP_TO_EDGE)
            return i < 0 ? 0 : (i >= n ? n - 1 : i);
        if (mode == RTPBR_GLTF_WRAP_MIRRORED_REPEAT) {
            int p = ((i % (2 * n)) + 2 * n) % (2 * n);
            return p < n ? p : 2 * n - 1 - p;
        }
        return ((i % n) + n) % n;
    }
    glm::vec4 texel(int x, int y) const {
        return texels_[size_t(wrap(y, int(h_), wrapT_)) * w_ + size_t(wrap(x, int(w_), wrapS_))];
    }

    uint32_t w_, h_;
    rtpbr_gltf_wrap wrapS_, wrapT_;
    bool nearest_ = false;
    std::vector<glm::vec4> texels_;
};

} // namespace rtpbr_oracle

#endif
