// The glTF 2.0 JSON schema's types and ranges, checked on the parsed document before
// tinygltf reads it: tinygltf replaces a value of the wrong type ("NaN", null, an object,
// "yes" for a boolean) by the default and stores indices in an int (4294967296 becomes 0),
// so a schema error would otherwise load as something else. Every property the schema
// defines for the core objects is checked (types, minimum/maximum, enums, array lengths,
// uniqueness of node lists, required properties); unknown properties, extensions and
// extras are left to the code that reads them, except KHR_lights_punctual, checked whole here
// (tinygltf 2.7 refuses a spot light without "spot", drops a node's extension that is not an
// object and casts integer literals in extension values to int). Errors are
// RTPBR_GLTF_ERROR_INVALID_JSON
// with a JSON pointer to the value; an index to an element that does not exist is
// RTPBR_GLTF_ERROR_INVALID_REFERENCE, whether or not the scene uses the referring object.
// (a KHR_lights_punctual number that overflows a float: RTPBR_GLTF_ERROR_NONFINITE; an unknown
// light type: RTPBR_GLTF_ERROR_UNSUPPORTED). A light's "extras": {"radius": r} is read here too
// (a point light's sphere, ctx.punctual_radii), and "length": L (its capsule,
// ctx.punctual_lengths): extras are free-form, so a radius or length that is not a number, one on
// a spot or directional light, or a length without a radius, is only a warning; a point light's
// number must be >= 0 and fit a float.
// Reference: the glTF 2.0 JSON schema, https://github.com/KhronosGroup/glTF/tree/main/specification/2.0/schema
// and KHR_lights_punctual's (extensions/2.0/Khronos/KHR_lights_punctual/schema there).
#include "scene_internal.hpp"

#include <nlohmann/json.hpp>

#include <map>
#include <set>

namespace rtpbr_gltf_detail {

namespace {

using json = nlohmann::json;

// glTF indices are "integer, minimum 0"; the loader stores them as int.
constexpr double kMaxIndex = 2147483647.0;

struct Checker {
    Context& ctx;
    const json& root;
    size_t punctual_count = 0;                // extensions.KHR_lights_punctual.lights
    std::vector<size_t> spots_without_cone;   // spot lights that have no "spot" object

    // "node 3 (/nodes/3/rotation)" for a JSON pointer into a top-level array.
    static std::string describe(const std::string& where) {
        const size_t slash = where.find('/', 1);
        if (where.size() < 2 || slash == std::string::npos) return where;
        std::string kind = where.substr(1, slash - 1);
        if (kind == "meshes") kind = "mesh";
        else if (!kind.empty() && kind.back() == 's') kind.pop_back();
        const size_t end = where.find('/', slash + 1);
        return kind + " " + where.substr(slash + 1, end == std::string::npos ? std::string::npos : end - slash - 1) +
               " (" + where + ")";
    }
    bool fail(const std::string& where, const char* what) {
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_JSON, "%s: %s", describe(where).c_str(), what);
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
        return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "%s: %s %.0f does not exist (%zu %s)", describe(where).c_str(), key,
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
        if (!accessor_in_view(a, at)) return false;
        // min and max have one element per component of the type.
        const size_t components = type_components(a["type"].get_ref<const std::string&>());
        for (const char* key : {"min", "max"}) {
            auto it = a.find(key);
            if (it != a.end() && it->size() != components)
                return fail(at + "/" + key, "needs one element per component of the accessor's type");
        }
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
    static size_t component_size(double type) {
        return type == 5120 || type == 5121 ? 1 : type == 5122 || type == 5123 ? 2 : 4;
    }
    static size_t type_components(const std::string& type) {
        static const std::pair<const char*, size_t> kComponents[] = {
            {"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}};
        for (const auto& c : kComponents)
            if (type == c.first) return c.second;
        return 0;
    }
    // The accessor's first byte aligned to its component size, and its last byte inside the
    // view (glTF 2.0 3.6.2.4; matrices' column padding is not modelled: the loader reads none).
    bool accessor_in_view(const json& a, const std::string& at) {
        auto vi = a.find("bufferView");
        if (vi == a.end()) return true;
        const json& view = root["bufferViews"][size_t(number(*vi))];
        if (!view.is_object()) return true;  // reported with the bufferViews
        auto num = [](const json& o, const char* key, double fallback) {
            auto it = o.find(key);
            return it != o.end() && it->is_number() ? it->get<double>() : fallback;
        };
        const size_t csize = component_size(number(a["componentType"]));
        const size_t element = csize * type_components(a["type"].get_ref<const std::string&>());
        const double offset = num(a, "byteOffset", 0), view_offset = num(view, "byteOffset", 0);
        if (std::fmod(offset + view_offset, double(csize)) != 0.0)
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                            "%s: byteOffset %.0f + bufferView byteOffset %.0f is not a multiple of %zu", describe(at).c_str(),
                            offset, view_offset, csize);
        const double stride = num(view, "byteStride", double(element));
        const double last = offset + stride * (number(a["count"]) - 1.0) + double(element);
        if (last > num(view, "byteLength", 0))
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                            "%s: byteOffset + count * stride needs %.0f bytes, exceeds bufferView %.0f (%.0f bytes)",
                            describe(at).c_str(), last, number(*vi), num(view, "byteLength", 0));
        return true;
    }
    bool buffer_view(const json& v, const std::string& at) {
        if (!common(v, at) || !index(v, at, "buffer", "buffers", true) || !integer(v, at, "byteOffset", 0, HUGE_VAL) ||
            !integer(v, at, "byteLength", 1, HUGE_VAL, true) || !soft_enum(v, at, "target", {34962, 34963}))
            return false;
        // The view within its buffer's declared length (the data's length is checked on use).
        auto buf = root.find("buffers");
        const size_t b = size_t(number(v["buffer"]));
        const json& buffer = (*buf)[b];
        const double offset = v.contains("byteOffset") ? number(v["byteOffset"]) : 0.0;
        if (buffer.is_object() && buffer.contains("byteLength") && buffer["byteLength"].is_number() &&
            offset + number(v["byteLength"]) > number(buffer["byteLength"]))
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_ACCESSOR,
                            "%s: byteOffset %.0f + byteLength %.0f exceeds buffer %zu (byteLength %.0f)", describe(at).c_str(),
                            offset, number(v["byteLength"]), b, number(buffer["byteLength"]));
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
               alpha_mode(m, at) &&
               real(m, at, "alphaCutoff", 0.0, HUGE_VAL) && boolean(m, at, "doubleSided");
    }
    // The Khronos validator only warns about an unknown alphaMode (as opaque); so does this.
    bool alpha_mode(const json& m, const std::string& at) {
        auto it = m.find("alphaMode");
        if (it == m.end()) return true;
        if (!it->is_string()) return fail(at + "/alphaMode", "must be a string");
        const std::string& mode = it->get_ref<const std::string&>();
        if (mode != "OPAQUE" && mode != "MASK" && mode != "BLEND")
            ctx.warn("%s/alphaMode: unknown value '%s' read as OPAQUE", at.c_str(), mode.size() > 40 ? "..." : mode.c_str());
        return true;
    }
    // Each texture of the primitive's material reads a TEXCOORD_n the primitive must have.
    bool texcoords_present(const json& primitive, const json& attributes, const std::string& at) {
        auto mi = primitive.find("material");
        if (mi == primitive.end() || !is_integer(*mi) || number(*mi) < 0 || number(*mi) >= double(count_of("materials")))
            return true;  // reported by index()
        const json& material = root["materials"][size_t(number(*mi))];
        if (!material.is_object()) return true;
        std::vector<const json*> infos;
        for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"})
            if (material.contains(key)) infos.push_back(&material[key]);
        auto pbr = material.find("pbrMetallicRoughness");
        if (pbr != material.end() && pbr->is_object())
            for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"})
                if (pbr->contains(key)) infos.push_back(&(*pbr)[key]);
        for (const json* info : infos) {
            if (!info->is_object()) continue;
            auto tc = info->find("texCoord");
            const double set = tc != info->end() && tc->is_number() ? number(*tc) : 0.0;
            if (!attributes.contains("TEXCOORD_" + std::to_string(static_cast<long long>(set))))
                return fail(at + "/attributes",
                            ("the material reads TEXCOORD_" + std::to_string(static_cast<long long>(set)) +
                             ", which the primitive does not have")
                                .c_str());
        }
        return true;
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
            for (auto it = attrs->begin(); it != attrs->end(); ++it) {
                if (!known_attribute(it.key())) return fail(q + "/attributes/" + it.key(), "not a glTF attribute name");
                if (!index(*attrs, q + "/attributes", it.key().c_str(), "accessors", true)) return false;
            }
            // A bufferView's target, when given, must match its use.
            auto view_target = [&](const json& accessor_index) -> double {
                const json& acc = root["accessors"][size_t(number(accessor_index))];
                if (!acc.is_object() || !acc.contains("bufferView")) return 0.0;
                const json& view = root["bufferViews"][size_t(number(acc["bufferView"]))];
                return view.is_object() && view.contains("target") && view["target"].is_number()
                           ? number(view["target"])
                           : 0.0;
            };
            // Vertex attributes sharing a bufferView need its byteStride (glTF 2.0 3.6.2.4).
            std::map<size_t, size_t> attribute_views;
            for (auto it = attrs->begin(); it != attrs->end(); ++it) {
                const json& acc = root["accessors"][size_t(number(it.value()))];
                if (acc.is_object() && acc.contains("bufferView")) ++attribute_views[size_t(number(acc["bufferView"]))];
            }
            for (const auto& uses : attribute_views)
                if (uses.second > 1 && !root["bufferViews"][uses.first].contains("byteStride"))
                    return fail(q + "/attributes", "attributes share a bufferView without byteStride");
            for (auto it = attrs->begin(); it != attrs->end(); ++it)
                if (view_target(it.value()) == 34963.0)
                    return fail(q + "/attributes/" + it.key(), "its bufferView's target is ELEMENT_ARRAY_BUFFER");
            if (!index(pr, q, "indices", "accessors")) return false;
            if (pr.contains("indices") && view_target(pr["indices"]) == 34962.0)
                return fail(q + "/indices", "its bufferView's target is ARRAY_BUFFER");
            if (!texcoords_present(pr, *attrs, q)) return false;
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
        // A matrix must be a TRS transform: its last row is (0, 0, 0, 1) (column-major).
        auto m = n.find("matrix");
        if (m != n.end() && m->is_array() && m->size() == 16) {
            bool numeric = true;
            for (const json& e : *m) numeric = numeric && e.is_number();
            if (numeric && (number((*m)[3]) != 0.0 || number((*m)[7]) != 0.0 || number((*m)[11]) != 0.0 ||
                            number((*m)[15]) != 1.0))
                return fail(at + "/matrix", "not a TRS transform (last row must be 0, 0, 0, 1)");
        }
        // rotation is a unit quaternion (the validator's tolerance is of this order).
        auto r = n.find("rotation");
        if (r != n.end() && r->is_array() && r->size() == 4) {
            double len2 = 0;
            for (const json& e : *r) len2 += e.is_number() ? number(e) * number(e) : 0.0;
            if (std::fabs(std::sqrt(len2) - 1.0) > 5e-3) return fail(at + "/rotation", "not a unit quaternion");
        }
        return common(n, at) && punctual_node(n, at) && index(n, at, "camera", "cameras") && indices(n, at, "children", "nodes") && index(n, at, "skin", "skins") &&
               numbers(n, at, "matrix", 16, -HUGE_VAL, HUGE_VAL) && index(n, at, "mesh", "meshes") &&
               numbers(n, at, "rotation", 4, -1.0, 1.0) && numbers(n, at, "scale", 3, -HUGE_VAL, HUGE_VAL) &&
               numbers(n, at, "translation", 3, -HUGE_VAL, HUGE_VAL) &&
               numbers(n, at, "weights", 0, -HUGE_VAL, HUGE_VAL);
    }

    // ---- KHR_lights_punctual ----
    // The schema's maximum outerConeAngle, 1.570796326794897: as a double one step above pi/2,
    // so that pi/2 written to any precision is accepted.
    static constexpr double kMaxConeAngle = 1.570796326794897;
    static constexpr double kDefaultOuterCone = 0.78539816339744830962;  // pi/4, the extension's default
    bool light_fail(rtpbr_gltf_result r, size_t light, const std::string& where, const char* what) {
        return ctx.fail(r, "KHR_lights_punctual light %zu (%s): %s", light, where.c_str(), what);
    }
    // An optional number of light `light`: a number (else INVALID_JSON), in [lo, hi] (lo itself
    // excluded when exclusive_lo; else INVALID_JSON, `range` says which), finite as a float
    // (else NONFINITE). *value keeps its default when absent.
    bool light_number(const json& o, size_t light, const std::string& at, const char* key, double lo, double hi,
                      bool exclusive_lo, const char* range, double* value) {
        auto it = o.find(key);
        if (it == o.end()) return true;
        const std::string p = at + "/" + key;
        if (!it->is_number()) return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, light, p, "must be a number");
        const double d = number(*it);
        if (!(d >= lo && d <= hi) || (exclusive_lo && d <= lo))
            return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, light, p, range);
        if (!fits_float(d)) return light_fail(RTPBR_GLTF_ERROR_NONFINITE, light, p, "not representable as a float");
        *value = d;
        return true;
    }
    bool punctual_light(const json& l, size_t i, const std::string& at) {
        if (!l.is_object()) return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, i, at, "must be an object");
        auto type = l.find("type");
        if (type == l.end()) return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, i, at + "/type", "required string missing");
        if (!type->is_string()) return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, i, at + "/type", "must be a string");
        const std::string& t = type->get_ref<const std::string&>();
        if (t != "point" && t != "spot" && t != "directional")
            return ctx.fail(RTPBR_GLTF_ERROR_UNSUPPORTED,
                            "KHR_lights_punctual light %zu (%s/type): type '%s' not supported (point, spot, directional)",
                            i, at.c_str(), t.size() > 40 ? "..." : t.c_str());
        auto color = l.find("color");
        if (color != l.end()) {
            const std::string p = at + "/color";
            if (!color->is_array() || color->size() != 3)
                return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, i, p, "must be an array of 3 numbers");
            for (const json& c : *color) {
                if (!c.is_number()) return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, i, p, "element is not a number");
                if (!(number(c) >= 0.0 && number(c) <= 1.0))
                    return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, i, p, "element out of [0, 1]");
            }
        }
        double unused = 0.0, inner = 0.0, outer = kDefaultOuterCone;
        if (!light_number(l, i, at, "intensity", 0.0, HUGE_VAL, false, "must be >= 0", &unused) ||
            !light_number(l, i, at, "range", 0.0, HUGE_VAL, true, "must be > 0", &unused) ||
            !punctual_radius(l, i, at, t))
            return false;
        auto spot = l.find("spot");
        if (spot == l.end()) {
            if (t == "spot") spots_without_cone.push_back(i);
            return true;
        }
        const std::string p = at + "/spot";
        if (!spot->is_object()) return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, i, p, "must be an object");
        if (!light_number(*spot, i, p, "innerConeAngle", 0.0, kMaxConeAngle, false, "must be in [0, pi/2]", &inner) ||
            !light_number(*spot, i, p, "outerConeAngle", 0.0, kMaxConeAngle, false, "must be in [0, pi/2]", &outer))
            return false;
        if (!(inner < outer))
            return light_fail(RTPBR_GLTF_ERROR_INVALID_JSON, i, p,
                              "innerConeAngle must be less than outerConeAngle (defaults 0 and pi/4)");
        return true;
    }
    // A light's "extras": {"radius": r, "length": L} (Blender writes a light's custom properties
    // to extras), into ctx.punctual_radii[i] and ctx.punctual_lengths[i]: a point light's sphere,
    // or its capsule (a segment of length L swept by the ball of radius r). Extras belong to
    // whoever wrote them: a value that is not a number, one on a spot or directional light, or a
    // length without a radius is ignored with a warning; a point light's number is held to the
    // rules of the extension's own numbers.
    bool punctual_radius(const json& l, size_t i, const std::string& at, const std::string& type) {
        auto extras = l.find("extras");
        if (extras == l.end() || !extras->is_object()) return true;
        double radius = 0.0, length = 0.0;
        if (!punctual_size(*extras, i, at, type, "radius", "only a point light is a sphere", &radius) ||
            !punctual_size(*extras, i, at, type, "length", "only a point light is a capsule", &length))
            return false;
        ctx.punctual_radii[i] = radius > 0.0 ? radius : 0.0;  // -0 is no radius
        if (length > 0.0 && !(radius > 0.0))
            ctx.warn("KHR_lights_punctual light %zu (%s/extras/length): length ignored without a radius (a capsule "
                     "needs radius > 0)", i, at.c_str());
        else
            ctx.punctual_lengths[i] = length > 0.0 ? length : 0.0;  // -0 is no length
        return true;
    }
    // One of a light's extras sizes (metres): 0 when absent, not a number (a warning) or on a
    // spot or directional light (a warning unless 0); else a number >= 0 that fits a float.
    bool punctual_size(const json& extras, size_t i, const std::string& at, const std::string& type, const char* key,
                       const char* only, double* value) {
        auto r = extras.find(key);
        if (r == extras.end()) return true;
        const std::string p = at + "/extras/" + key;
        if (!r->is_number()) {
            ctx.warn("KHR_lights_punctual light %zu (%s): not a number: ignored (no %s)", i, p.c_str(), key);
            return true;
        }
        if (type != "point") {
            if (number(*r) != 0.0)
                ctx.warn("KHR_lights_punctual light %zu (%s): %s ignored on a %s light (%s)", i, p.c_str(), key,
                         type.c_str(), only);
            return true;
        }
        return light_number(extras, i, at + "/extras", key, 0.0, HUGE_VAL, false, "must be >= 0", value);
    }
    // The root's extensions.KHR_lights_punctual: an object with an array of lights.
    bool punctual_root() {
        auto ext = root.find("extensions");
        if (ext == root.end() || !ext->is_object()) return true;  // reported by object()
        auto k = ext->find("KHR_lights_punctual");
        if (k == ext->end()) return true;
        const std::string at = "/extensions/KHR_lights_punctual";
        if (!k->is_object()) return fail(at, "must be an object");
        auto lights = k->find("lights");
        if (lights == k->end()) return fail(at + "/lights", "required array missing");
        if (!lights->is_array()) return fail(at + "/lights", "must be an array of lights");
        punctual_count = lights->size();
        ctx.punctual_radii.assign(punctual_count, 0.0);
        ctx.punctual_lengths.assign(punctual_count, 0.0);
        for (size_t i = 0; i < lights->size(); ++i)
            if (!punctual_light((*lights)[i], i, at + "/lights/" + std::to_string(i))) return false;
        return true;
    }
    // A node's extensions.KHR_lights_punctual: {"light": index into the lights}.
    bool punctual_node(const json& n, const std::string& at) {
        auto ext = n.find("extensions");
        if (ext == n.end() || !ext->is_object()) return true;  // reported by common()
        auto k = ext->find("KHR_lights_punctual");
        if (k == ext->end()) return true;
        const std::string p = at + "/extensions/KHR_lights_punctual";
        if (!k->is_object()) return fail(p, "must be an object");
        if (!integer(*k, p, "light", 0.0, kMaxIndex, true)) return false;
        const double light = number((*k)["light"]);
        if (light >= double(punctual_count))
            return ctx.fail(RTPBR_GLTF_ERROR_INVALID_REFERENCE, "%s: KHR_lights_punctual light %.0f does not exist (%zu lights)",
                            describe(p + "/light").c_str(), light, punctual_count);
        return true;
    }

    // An integer outside the enum is only a warning for the Khronos validator where the reader
    // has a sensible default (bufferView target, sampler filters and wraps); so it is here.
    bool soft_enum(const json& o, const std::string& at, const char* key, std::initializer_list<int> values) {
        if (!integer(o, at, key, -HUGE_VAL, HUGE_VAL)) return false;
        auto it = o.find(key);
        if (it == o.end()) return true;
        for (int v : values)
            if (number(*it) == double(v)) return true;
        ctx.warn("%s/%s: unknown value %.0f, the default is used", at.c_str(), key, number(*it));
        return true;
    }
    bool sampler(const json& s, const std::string& at) {
        return common(s, at) && soft_enum(s, at, "magFilter", {9728, 9729}) &&
               soft_enum(s, at, "minFilter", {9728, 9729, 9984, 9985, 9986, 9987}) &&
               soft_enum(s, at, "wrapS", {33071, 33648, 10497}) && soft_enum(s, at, "wrapT", {33071, 33648, 10497});
    }
    bool scene(const json& s, const std::string& at) { return common(s, at) && indices(s, at, "nodes", "nodes"); }
    bool texture(const json& t, const std::string& at) {
        return common(t, at) && index(t, at, "sampler", "samplers") && index(t, at, "source", "images");
    }
    bool any(const json& o, const std::string& at) { return common(o, at); }
    // "^[0-9]+\\.[0-9]+$" (asset.version, asset.minVersion).
    bool version_pattern(const json& asset, const char* key) {
        auto it = asset.find(key);
        if (it == asset.end() || !it->is_string()) return true;
        const std::string& v = it->get_ref<const std::string&>();
        const size_t dot = v.find('.');
        auto digits = [](const std::string& t) {
            return !t.empty() && t.find_first_not_of("0123456789") == std::string::npos;
        };
        if (dot == std::string::npos || !digits(v.substr(0, dot)) || !digits(v.substr(dot + 1)))
            return fail(std::string("/asset/") + key, "must look like 2.0");
        return true;
    }
    // Attribute semantics of glTF 2.0 (3.7.2.1), or application-specific ones starting with '_'.
    static bool known_attribute(const std::string& name) {
        if (name == "POSITION" || name == "NORMAL" || name == "TANGENT" || (!name.empty() && name[0] == '_'))
            return true;
        for (const char* prefix : {"TEXCOORD_", "COLOR_", "JOINTS_", "WEIGHTS_"}) {
            const std::string p(prefix);
            if (name.compare(0, p.size(), p) == 0 && name.size() > p.size() &&
                name.find_first_not_of("0123456789", p.size()) == std::string::npos &&
                (name.size() == p.size() + 1 || name[p.size()] != '0'))
                return true;
        }
        return false;
    }

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
        if (!string(*asset, "/asset", "version", true) || !version_pattern(*asset, "version") ||
            !version_pattern(*asset, "minVersion") || !string(*asset, "/asset", "minVersion") ||
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
               index(root, "", "scene", "scenes") && object(root, "", "extensions") && punctual_root() &&
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

bool check_schema(Context& ctx, const char* json_text, size_t size, std::string* rewritten) {
    // A syntax error is left to tinygltf, whose message names the position.
    json doc = json::parse(json_text, json_text + size, nullptr, false);
    if (doc.is_discarded()) return true;
    Checker checker{ctx, doc, 0, {}};
    if (!checker.run()) return false;
    if (!checker.spots_without_cone.empty()) {
        // "When the spot property is omitted, a spot light must use default values" (the
        // extension's text); tinygltf 2.7 refuses the file instead, so it gets an empty "spot".
        json& lights = doc["extensions"]["KHR_lights_punctual"]["lights"];
        for (size_t i : checker.spots_without_cone) lights[i]["spot"] = json::object();
        *rewritten = doc.dump();
    }
    return true;
}

}  // namespace rtpbr_gltf_detail
