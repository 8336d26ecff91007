// The glTF 2.0 JSON schema's types and ranges, checked on the parsed document before
// tinygltf reads it: tinygltf replaces a value of the wrong type ("NaN", null, an object,
// "yes" for a boolean) by the default and stores indices in an int (4294967296 becomes 0),
// so a schema error would otherwise load as something else. Every property the schema
// defines for the core objects is checked (types, minimum/maximum, enums, array lengths,
// uniqueness of node lists, required properties); unknown properties, extensions and
// extras are left to the code that reads them. Errors are RTPBR_SCENE_ERROR_INVALID_JSON
// with a JSON pointer to the value; an index to an element that does not exist is
// RTPBR_SCENE_ERROR_INVALID_REFERENCE, whether or not the scene uses the referring object.
// Reference: the glTF 2.0 JSON schema, https://github.com/KhronosGroup/glTF/tree/main/specification/2.0/schema
#include "scene_internal.hpp"

#include <nlohmann/json.hpp>

#include <set>

namespace rtpbr_scene_detail {

namespace {

using json = nlohmann::json;

// glTF indices are "integer, minimum 0"; the loader stores them as int.
constexpr double kMaxIndex = 2147483647.0;

struct Checker {
    Context& ctx;
    const json& root;

    bool fail(const std::string& where, const char* what) {
        return ctx.fail(RTPBR_SCENE_ERROR_INVALID_JSON, "%s: %s", where.c_str(), what);
    }

    static bool is_integer(const json& v) {
        if (v.is_number_integer() || v.is_number_unsigned()) return true;
        if (!v.is_number_float()) return false;
        const double d = v.get<double>();
        return std::isfinite(d) && d == std::floor(d);
    }
    static double number(const json& v) { return v.get<double>(); }

    // ---- scalar kinds ----
    bool integer(const json& o, const std::string& at, const char* key, double lo, double hi, bool required = false) {
        auto it = o.find(key);
        if (it == o.end()) return required ? fail(at + "/" + key, "required integer missing") : true;
        if (!is_integer(*it)) return fail(at + "/" + key, "must be an integer");
        const double d = number(*it);
        if (d < lo || d > hi) return fail(at + "/" + key, "integer out of range");
        return true;
    }
    // Number of elements of the top-level array `name` (0 if absent or not an array).
    size_t count_of(const char* name) const {
        auto it = root.find(name);
        return it != root.end() && it->is_array() ? it->size() : 0;
    }
    bool unresolved(const std::string& where, const char* key, double value, const char* target) {
        return ctx.fail(RTPBR_SCENE_ERROR_INVALID_REFERENCE, "%s: %s %.0f does not exist (%zu %s)", where.c_str(), key,
                        value, count_of(target), target);
    }
    // An index into the top-level array `target`: an integer in range, and the element exists.
    bool index(const json& o, const std::string& at, const char* key, const char* target, bool required = false) {
        if (!integer(o, at, key, 0.0, kMaxIndex, required)) return false;
        auto it = o.find(key);
        // Attribute names are keys of their own: name the target ("accessor 9") there.
        const char* noun = std::string(target) == "accessors" ? "accessor" : key;
        if (it != o.end() && number(*it) >= double(count_of(target)))
            return unresolved(at + "/" + key, noun, number(*it), target);
        return true;
    }
    bool real(const json& o, const std::string& at, const char* key, double lo, double hi, bool required = false,
              bool exclusive_lo = false) {
        auto it = o.find(key);
        if (it == o.end()) return required ? fail(at + "/" + key, "required number missing") : true;
        if (!it->is_number()) return fail(at + "/" + key, "must be a number");
        const double d = number(*it);
        if (!(d >= lo && d <= hi) || (exclusive_lo && d <= lo)) return fail(at + "/" + key, "number out of range");
        return true;
    }
    bool boolean(const json& o, const std::string& at, const char* key) {
        auto it = o.find(key);
        if (it != o.end() && !it->is_boolean()) return fail(at + "/" + key, "must be true or false");
        return true;
    }
    bool string(const json& o, const std::string& at, const char* key, bool required = false) {
        auto it = o.find(key);
        if (it == o.end()) return required ? fail(at + "/" + key, "required string missing") : true;
        if (!it->is_string()) return fail(at + "/" + key, "must be a string");
        return true;
    }
    bool object(const json& o, const std::string& at, const char* key) {
        auto it = o.find(key);
        if (it != o.end() && !it->is_object()) return fail(at + "/" + key, "must be an object");
        return true;
    }
    bool int_enum(const json& o, const std::string& at, const char* key, std::initializer_list<int> values,
                  bool required = false) {
        auto it = o.find(key);
        if (it == o.end()) return required ? fail(at + "/" + key, "required enum missing") : true;
        if (!is_integer(*it)) return fail(at + "/" + key, "must be an integer");
        const double d = number(*it);
        for (int v : values)
            if (d == double(v)) return true;
        return fail(at + "/" + key, "value not allowed by the schema");
    }
    bool string_enum(const json& o, const std::string& at, const char* key, std::initializer_list<const char*> values,
                     bool required = false) {
        auto it = o.find(key);
        if (it == o.end()) return required ? fail(at + "/" + key, "required enum missing") : true;
        if (!it->is_string()) return fail(at + "/" + key, "must be a string");
        for (const char* v : values)
            if (it->get_ref<const std::string&>() == v) return true;
        return fail(at + "/" + key, "value not allowed by the schema");
    }
    // Array of numbers of a fixed length (0: any length >= min_items), each in [lo, hi].
    bool numbers(const json& o, const std::string& at, const char* key, size_t length, double lo, double hi,
                 size_t min_items = 1, size_t max_items = SIZE_MAX) {
        auto it = o.find(key);
        if (it == o.end()) return true;
        if (!it->is_array()) return fail(at + "/" + key, "must be an array of numbers");
        const size_t n = it->size();
        if (length ? n != length : (n < min_items || n > max_items)) return fail(at + "/" + key, "wrong array length");
        for (const json& e : *it)
            if (!e.is_number() || !(number(e) >= lo && number(e) <= hi))
                return fail(at + "/" + key, "element is not a number in range");
        return true;
    }
    // Array of unique indices, at least one.
    bool indices(const json& o, const std::string& at, const char* key, const char* target) {
        auto it = o.find(key);
        if (it == o.end()) return true;
        if (!it->is_array() || it->empty()) return fail(at + "/" + key, "must be a non-empty array of indices");
        std::set<double> seen;
        for (const json& e : *it) {
            if (!is_integer(e) || number(e) < 0.0 || number(e) > kMaxIndex)
                return fail(at + "/" + key, "element is not an index");
            if (!seen.insert(number(e)).second) return fail(at + "/" + key, "indices must be unique");
            if (number(e) >= double(count_of(target))) return unresolved(at + "/" + key, "node", number(e), target);
        }
        return true;
    }
    bool strings(const json& o, const std::string& at, const char* key) {
        auto it = o.find(key);
        if (it == o.end()) return true;
        if (!it->is_array() || it->empty()) return fail(at + "/" + key, "must be a non-empty array of strings");
        std::set<std::string> seen;
        for (const json& e : *it) {
            if (!e.is_string()) return fail(at + "/" + key, "element is not a string");
            if (!seen.insert(e.get<std::string>()).second) return fail(at + "/" + key, "strings must be unique");
        }
        return true;
    }
    // Properties every glTF object may have.
    bool common(const json& o, const std::string& at) {
        return string(o, at, "name") && object(o, at, "extensions");
    }
    bool texture_info(const json& o, const std::string& at, const char* key, const char* extra = nullptr) {
        auto it = o.find(key);
        if (it == o.end()) return true;
        const std::string p = at + "/" + key;
        if (!it->is_object()) return fail(p, "must be an object");
        if (extra && std::string(extra) == "scale" && !real(*it, p, "scale", -HUGE_VAL, HUGE_VAL)) return false;
        if (extra && std::string(extra) == "strength" && !real(*it, p, "strength", 0.0, 1.0)) return false;
        return integer(*it, p, "texCoord", 0, kMaxIndex) && object(*it, p, "extensions") &&
               index(*it, p, "index", "textures", true);
    }

    // ---- objects ----
    bool accessor(const json& a, const std::string& at) {
        if (!common(a, at) || !index(a, at, "bufferView", "bufferViews") || !integer(a, at, "byteOffset", 0, HUGE_VAL) ||
            !int_enum(a, at, "componentType", {5120, 5121, 5122, 5123, 5125, 5126}, true) ||
            !boolean(a, at, "normalized") || !integer(a, at, "count", 1, HUGE_VAL, true) ||
            !string_enum(a, at, "type", {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}, true) ||
            !numbers(a, at, "max", 0, -HUGE_VAL, HUGE_VAL, 1, 16) || !numbers(a, at, "min", 0, -HUGE_VAL, HUGE_VAL, 1, 16))
            return false;
        auto sp = a.find("sparse");
        if (sp == a.end()) return true;
        const std::string p = at + "/sparse";
        if (!sp->is_object()) return fail(p, "must be an object");
        if (!integer(*sp, p, "count", 1, HUGE_VAL, true)) return false;
        for (const char* part : {"indices", "values"}) {
            auto it = sp->find(part);
            const std::string q = p + "/" + part;
            if (it == sp->end()) return fail(q, "required object missing");
            if (!it->is_object()) return fail(q, "must be an object");
            if (!index(*it, q, "bufferView", "bufferViews", true) || !integer(*it, q, "byteOffset", 0, HUGE_VAL)) return false;
            if (std::string(part) == "indices" && !int_enum(*it, q, "componentType", {5121, 5123, 5125}, true))
                return false;
        }
        return true;
    }
    bool buffer_view(const json& v, const std::string& at) {
        if (!common(v, at) || !index(v, at, "buffer", "buffers", true) || !integer(v, at, "byteOffset", 0, HUGE_VAL) ||
            !integer(v, at, "byteLength", 1, HUGE_VAL, true) || !int_enum(v, at, "target", {34962, 34963}))
            return false;
        auto it = v.find("byteStride");
        if (it != v.end() &&
            (!integer(v, at, "byteStride", 4, 252) || std::fmod(number(*it), 4.0) != 0.0))
            return ctx.failed() ? false : fail(at + "/byteStride", "must be a multiple of 4");
        return true;
    }
    bool buffer(const json& b, const std::string& at) {
        return common(b, at) && string(b, at, "uri") && integer(b, at, "byteLength", 1, HUGE_VAL, true);
    }
    bool camera(const json& c, const std::string& at) {
        if (!common(c, at) || !string_enum(c, at, "type", {"perspective", "orthographic"}, true)) return false;
        for (const char* kind : {"perspective", "orthographic"}) {
            auto it = c.find(kind);
            if (it == c.end()) continue;
            const std::string p = at + "/" + kind;
            if (!it->is_object()) return fail(p, "must be an object");
            if (std::string(kind) == "perspective") {
                if (!real(*it, p, "aspectRatio", 0.0, HUGE_VAL, false, true) ||
                    !real(*it, p, "yfov", 0.0, HUGE_VAL, true, true) ||
                    !real(*it, p, "zfar", 0.0, HUGE_VAL, false, true) ||
                    !real(*it, p, "znear", 0.0, HUGE_VAL, true, true))
                    return false;
            } else if (!real(*it, p, "xmag", -HUGE_VAL, HUGE_VAL, true) ||
                       !real(*it, p, "ymag", -HUGE_VAL, HUGE_VAL, true) ||
                       !real(*it, p, "zfar", 0.0, HUGE_VAL, true, true) || !real(*it, p, "znear", 0.0, HUGE_VAL, true)) {
                return false;
            }
        }
        const std::string& type = c["type"].get_ref<const std::string&>();
        if (!c.contains(type)) return fail(at + "/" + type, "required object missing");
        return true;
    }
    bool image(const json& i, const std::string& at) {
        return common(i, at) && string(i, at, "uri") && string_enum(i, at, "mimeType", {"image/jpeg", "image/png"}) &&
               index(i, at, "bufferView", "bufferViews");
    }
    bool material(const json& m, const std::string& at) {
        if (!common(m, at)) return false;
        auto pbr = m.find("pbrMetallicRoughness");
        if (pbr != m.end()) {
            const std::string p = at + "/pbrMetallicRoughness";
            if (!pbr->is_object()) return fail(p, "must be an object");
            if (!numbers(*pbr, p, "baseColorFactor", 4, 0.0, 1.0) || !real(*pbr, p, "metallicFactor", 0.0, 1.0) ||
                !real(*pbr, p, "roughnessFactor", 0.0, 1.0) || !texture_info(*pbr, p, "baseColorTexture") ||
                !texture_info(*pbr, p, "metallicRoughnessTexture") || !object(*pbr, p, "extensions"))
                return false;
        }
        return texture_info(m, at, "normalTexture", "scale") && texture_info(m, at, "occlusionTexture", "strength") &&
               texture_info(m, at, "emissiveTexture") && numbers(m, at, "emissiveFactor", 3, 0.0, 1.0) &&
               string_enum(m, at, "alphaMode", {"OPAQUE", "MASK", "BLEND"}) &&
               real(m, at, "alphaCutoff", 0.0, HUGE_VAL) && boolean(m, at, "doubleSided");
    }
    bool mesh(const json& m, const std::string& at) {
        if (!common(m, at) || !numbers(m, at, "weights", 0, -HUGE_VAL, HUGE_VAL)) return false;
        auto prims = m.find("primitives");
        const std::string p = at + "/primitives";
        if (prims == m.end()) return fail(p, "required array missing");
        if (!prims->is_array() || prims->empty()) return fail(p, "must be a non-empty array of objects");
        for (size_t i = 0; i < prims->size(); ++i) {
            const json& pr = (*prims)[i];
            const std::string q = p + "/" + std::to_string(i);
            if (!pr.is_object()) return fail(q, "must be an object");
            auto attrs = pr.find("attributes");
            if (attrs == pr.end()) return fail(q + "/attributes", "required object missing");
            if (!attrs->is_object() || attrs->empty()) return fail(q + "/attributes", "must be a non-empty object");
            for (auto it = attrs->begin(); it != attrs->end(); ++it)
                if (!index(*attrs, q + "/attributes", it.key().c_str(), "accessors", true)) return false;
            if (!index(pr, q, "indices", "accessors") || !index(pr, q, "material", "materials") || !int_enum(pr, q, "mode", {0, 1, 2, 3, 4, 5, 6}) ||
                !object(pr, q, "extensions"))
                return false;
            auto targets = pr.find("targets");
            if (targets != pr.end()) {
                if (!targets->is_array() || targets->empty()) return fail(q + "/targets", "must be a non-empty array");
                for (const json& t : *targets) {
                    if (!t.is_object()) return fail(q + "/targets", "element is not an object");
                    for (auto it = t.begin(); it != t.end(); ++it)
                        if (!index(t, q + "/targets", it.key().c_str(), "accessors", true)) return false;
                }
            }
        }
        return true;
    }
    bool node(const json& n, const std::string& at) {
        return common(n, at) && index(n, at, "camera", "cameras") && indices(n, at, "children", "nodes") && index(n, at, "skin", "skins") &&
               numbers(n, at, "matrix", 16, -HUGE_VAL, HUGE_VAL) && index(n, at, "mesh", "meshes") &&
               numbers(n, at, "rotation", 4, -1.0, 1.0) && numbers(n, at, "scale", 3, -HUGE_VAL, HUGE_VAL) &&
               numbers(n, at, "translation", 3, -HUGE_VAL, HUGE_VAL) &&
               numbers(n, at, "weights", 0, -HUGE_VAL, HUGE_VAL);
    }
    bool sampler(const json& s, const std::string& at) {
        return common(s, at) && int_enum(s, at, "magFilter", {9728, 9729}) &&
               int_enum(s, at, "minFilter", {9728, 9729, 9984, 9985, 9986, 9987}) &&
               int_enum(s, at, "wrapS", {33071, 33648, 10497}) && int_enum(s, at, "wrapT", {33071, 33648, 10497});
    }
    bool scene(const json& s, const std::string& at) { return common(s, at) && indices(s, at, "nodes", "nodes"); }
    bool texture(const json& t, const std::string& at) {
        return common(t, at) && index(t, at, "sampler", "samplers") && index(t, at, "source", "images");
    }
    bool any(const json& o, const std::string& at) { return common(o, at); }

    template <typename F>
    bool array_of(const char* key, F check) {
        auto it = root.find(key);
        if (it == root.end()) return true;
        const std::string at = std::string("/") + key;
        // An empty array is an error for the schema (minItems 1) but means "none" to every
        // reader; it is accepted (one of the listed exceptions in tests/scene/validator_diff.py).
        if (!it->is_array()) return fail(at, "must be an array of objects");
        for (size_t i = 0; i < it->size(); ++i) {
            const json& o = (*it)[i];
            const std::string p = at + "/" + std::to_string(i);
            if (!o.is_object()) return fail(p, "must be an object");
            if (!(this->*check)(o, p)) return false;
        }
        return true;
    }

    bool run() {
        if (!root.is_object()) return fail("/", "the document must be a JSON object");
        auto asset = root.find("asset");
        if (asset == root.end()) return fail("/asset", "required object missing");
        if (!asset->is_object()) return fail("/asset", "must be an object");
        if (!string(*asset, "/asset", "version", true) || !string(*asset, "/asset", "minVersion") ||
            !string(*asset, "/asset", "generator") || !string(*asset, "/asset", "copyright") ||
            !object(*asset, "/asset", "extensions"))
            return false;
        if (!strings(root, "", "extensionsUsed") || !strings(root, "", "extensionsRequired")) return false;
        // Every required extension must be listed as used.
        auto required = root.find("extensionsRequired");
        if (required != root.end()) {
            auto used = root.find("extensionsUsed");
            for (const json& name : *required) {
                bool listed = false;
                if (used != root.end())
                    for (const json& u : *used) listed = listed || u == name;
                if (!listed) return fail("/extensionsRequired", "every entry must also be in extensionsUsed");
            }
        }
        return
               index(root, "", "scene", "scenes") && object(root, "", "extensions") &&
               array_of("accessors", &Checker::accessor) && array_of("animations", &Checker::any) &&
               array_of("buffers", &Checker::buffer) && array_of("bufferViews", &Checker::buffer_view) &&
               array_of("cameras", &Checker::camera) && array_of("images", &Checker::image) &&
               array_of("materials", &Checker::material) && array_of("meshes", &Checker::mesh) &&
               array_of("nodes", &Checker::node) && array_of("samplers", &Checker::sampler) &&
               array_of("scenes", &Checker::scene) && array_of("skins", &Checker::any) &&
               array_of("textures", &Checker::texture);
    }
};

}  // namespace

bool check_schema(Context& ctx, const char* json_text, size_t size) {
    // A syntax error is left to tinygltf, whose message names the position.
    json doc = json::parse(json_text, json_text + size, nullptr, false);
    if (doc.is_discarded()) return true;
    return Checker{ctx, doc}.run();
}

}  // namespace rtpbr_scene_detail
