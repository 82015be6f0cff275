// The JSON scene loader on bad input: every kind of mistake gives one InputError line
// "<file>: <JSON pointer>: <message>" with the RFC 6901 pointer of the offending value.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "scene/scene.h"
#include "test_paths.h"

namespace {

const std::string kCamera = R"({"lookfrom":[0,0,5],"lookat":[0,0,0],"vup":[0,1,0],"vfov":40,"width":8,"height":8})";
const std::string kMaterials = R"({"m":{"type":"lambertian","albedo":[0.5,0.5,0.5]},"lamp":{"type":"diffuse_light","emit":[1,1,1]}})";
const std::string kSphere = R"({"type":"sphere","center":[0,0,0],"radius":1,"material":"m"})";

/// A valid scene with one part replaced.
std::string scene(const std::string& camera = kCamera, const std::string& materials = kMaterials,
                  const std::string& objects = "[" + kSphere + "]", const std::string& extra = "") {
    return "{\"camera\":" + camera + ",\"materials\":" + materials + ",\"objects\":" + objects + extra + "}";
}
std::string withCamera(const std::string& c) { return scene(c); }
std::string withMaterials(const std::string& m) { return scene(kCamera, m); }
std::string withObjects(const std::string& o) { return scene(kCamera, kMaterials, o); }
std::string withObject(const std::string& o) { return withObjects("[" + o + "]"); }
std::string withEnv(const std::string& e) { return scene(kCamera, kMaterials, "[" + kSphere + "]", ",\"environment\":" + e); }
std::string withRender(const std::string& r) { return scene(kCamera, kMaterials, "[" + kSphere + "]", ",\"render\":" + r); }
/// The camera with one key set to a raw JSON value.
std::string cameraWith(const std::string& key, const std::string& value) {
    std::string c = kCamera;
    const std::string k = "\"" + key + "\":";
    if (auto at = c.find(k); at != std::string::npos) {
        const std::size_t start = at + k.size();
        std::size_t end = start;
        int depth = 0;
        for (; end < c.size(); ++end) {
            if (c[end] == '[') ++depth;
            if (c[end] == ']') --depth;
            if (depth == 0 && (c[end] == ',' || c[end] == '}')) break;
        }
        c.replace(start, end - start, value);
    } else {
        c.insert(c.size() - 1, "," + k + value);
    }
    return withCamera(c);
}
/// The sphere with extra members (",\"key\":value...").
std::string sphereWith(const std::string& members) {
    return withObject(R"({"type":"sphere","center":[0,0,0],"material":"m")" + members + "}");
}

struct Case {
    const char* name;
    std::string text;
    std::string where;     ///< the JSON pointer (or "line L, column C", "(document)")
    std::string fragment;  ///< part of the message after it
};

std::vector<Case> cases() {
    return {
        // JSON syntax and document shape
        {"syntax", "{\n  \"camera\": ,\n}", "line 2, column 13", "invalid JSON"},
        {"empty_file", "", "line 1, column 1", "invalid JSON"},
        {"trailing_garbage", scene() + " x", "line 1, column", "invalid JSON"},
        {"double_overflow", cameraWith("vfov", "1e400"), "/camera/vfov", "number overflow"},
        {"duplicate_key", sphereWith(R"(,"radius":1,"radius":2)"), "/objects/0/radius", "duplicate key"},
        {"root_not_object", "[1,2]", "(document)", "must be an object (got array"},
        {"too_deep", std::string(300, '[') + std::string(300, ']'), "/0/0/0/0", "nested deeper than 256 levels"},
        {"unknown_top_key", scene(kCamera, kMaterials, "[]", ",\"lights\":[]"), "/lights", "unknown key"},
        {"description_type", scene(kCamera, kMaterials, "[]", ",\"description\":7"), "/description", "must be a string"},
        {"material_without_materials", R"({"objects":[{"type":"sphere","center":[0,0,0],"radius":1,"material":"m"}]})",
         "/objects/0/material", "unknown material \"m\" (not a key of /materials)"},
        {"misspelt_key", R"({"camra":{},"materials":{},"objects":[]})", "/camra", "is it a misspelling of \"camera\"?"},
        {"missing_objects", R"({"camera":)" + kCamera + R"(,"materials":{}})", "/objects", "missing required key"},
        // camera
        {"camera_type", withCamera("[]"), "/camera", "must be an object"},
        {"camera_unknown_key", cameraWith("fov", "40"), "/camera/fov", "unknown key (allowed here: lookfrom"},
        {"vec3_type", cameraWith("lookfrom", "\"here\""), "/camera/lookfrom", "must be an array of 3 numbers (got string \"here\")"},
        {"vec3_length", cameraWith("lookfrom", "[0,5]"), "/camera/lookfrom", "must be an array of 3 numbers"},
        {"vec3_element_type", cameraWith("lookfrom", "[0,null,5]"), "/camera/lookfrom/1", "must be a number (got null)"},
        {"float_overflow", cameraWith("lookat", "[1e39,0,0]"), "/camera/lookat", "is too far from lookfrom (distance overflows a float)"},
        {"vfov_zero", cameraWith("vfov", "0"), "/camera/vfov", "must be in (0, 180) (got 0)"},
        {"vfov_180", cameraWith("vfov", "180"), "/camera/vfov", "must be in (0, 180) (got 180)"},
        {"width_zero", cameraWith("width", "0"), "/camera/width", "must be an integer in [1, 16384] (got 0)"},
        {"width_fraction", cameraWith("width", "8.5"), "/camera/width", "must be an integer in [1, 16384] (got 8.5)"},
        {"width_huge", cameraWith("width", "16385"), "/camera/width", "(got 16385)"},
        {"height_negative", cameraWith("height", "-8"), "/camera/height", "(got -8)"},
        {"height_string", cameraWith("height", "\"8\""), "/camera/height", "(got string \"8\")"},
        {"defocus_negative", cameraWith("defocus_angle", "-1"), "/camera/defocus_angle", "must be in [0, 180) (got -1)"},
        {"focus_zero", cameraWith("focus_dist", "0"), "/camera/focus_dist", "must be > 0 (got 0)"},
        {"lookat_is_lookfrom", cameraWith("lookat", "[0,0,5]"), "/camera/lookat", "must differ from lookfrom"},
        {"vup_zero", cameraWith("vup", "[0,0,0]"), "/camera/vup", "must not be zero"},
        {"vup_default_vertical", withCamera(R"({"lookfrom":[0,5,0],"lookat":[0,0,0],"vfov":40,"width":8,"height":8})"), "/camera",
         "the view direction lookat - lookfrom is vertical: give \"vup\""},
        // Punctual lights.
        {"point_light_no_intensity", withObject(R"({"type":"point_light","position":[0,2,0]})"), "/objects/0",
         "a point_light needs \"intensity\" (W/sr) or \"power\" (W)"},
        {"point_light_both", withObject(R"({"type":"point_light","position":[0,2,0],"intensity":[1,1,1],"power":[1,1,1]})"),
         "/objects/0/power", "give either intensity (W/sr) or power (W), not both"},
        {"point_light_negative", withObject(R"({"type":"point_light","position":[0,2,0],"intensity":[1,-1,1]})"),
         "/objects/0/intensity/1", "must be >= 0"},
        {"point_light_material", withObject(R"({"type":"point_light","position":[0,2,0],"intensity":[1,1,1],"material":"m"})"),
         "/objects/0/material", "unknown key"},
        {"spot_light_no_direction", withObject(R"({"type":"spot_light","position":[0,2,0],"intensity":[1,1,1]})"),
         "/objects/0/direction", "missing required key"},
        {"spot_light_inner_outer",
         withObject(R"({"type":"spot_light","position":[0,2,0],"direction":[0,-1,0],"intensity":[1,1,1],"inner_angle":30,"outer_angle":20})"),
         "/objects/0/inner_angle", "must be at most outer_angle"},
        {"spot_light_outer_zero",
         withObject(R"({"type":"spot_light","position":[0,2,0],"direction":[0,-1,0],"intensity":[1,1,1],"outer_angle":0})"),
         "/objects/0/outer_angle", "must be > 0"},
        {"spot_light_outer_wide",
         withObject(R"({"type":"spot_light","position":[0,2,0],"direction":[0,-1,0],"intensity":[1,1,1],"outer_angle":100})"),
         "/objects/0/outer_angle", "must be in [0, 90]"},
        {"directional_light_zero", withObject(R"({"type":"directional_light","direction":[0,0,0],"irradiance":[1,1,1]})"),
         "/objects/0/direction", "must not be zero"},
        {"directional_light_position", withObject(R"({"type":"directional_light","direction":[0,-1,0],"irradiance":[1,1,1],"position":[0,0,0]})"),
         "/objects/0/position", "unknown key"},
        {"light_type_misspelt", withObject(R"({"type":"point_lamp","position":[0,2,0]})"), "/objects/0/type", "point_light"},
        {"vup_parallel", cameraWith("vup", "[0,0,-2]"), "/camera/vup", "must not be parallel to the view direction"},
        // render
        {"render_type", withRender("true"), "/render", "must be an object (got true)"},
        {"spp_zero", withRender(R"({"spp":0})"), "/render/spp", "must be an integer in [1, 16777216] (got 0)"},
        {"max_depth_zero", withRender(R"({"max_depth":0})"), "/render/max_depth", "(got 0)"},
        {"roulette_depth_zero", withRender(R"({"roulette_depth":0})"), "/render/roulette_depth", "(got 0)"},
        {"seed_negative", withRender(R"({"seed":-1})"), "/render/seed", "must be an integer in [0, 4294967295] (got -1)"},
        {"seed_too_big", withRender(R"({"seed":4294967296})"), "/render/seed", "(got 4294967296)"},
        {"background_negative", withRender(R"({"background":[0,0,-0.5]})"), "/render/background/2", "must be in [0, 4e+15] (got -0.5)"},
        // Issue 15, defect 5: radiance whose sums would overflow gave NaN pixels and "0 non-finite samples".
        {"background_overflows", withRender(R"({"background":[1,3e38,1]})"), "/render/background/1", "must be in [0, 4e+15] (got 3e+38)"},
        {"render_unknown_key", withRender(R"({"samples":4})"), "/render/samples", "unknown key"},
        // materials
        {"materials_type", withMaterials("[]"), "/materials", "must be an object (got array"},
        {"material_type_missing", withMaterials(R"({"m":{"albedo":[1,1,1]}})"), "/materials/m/type", "missing required key"},
        {"material_type_unknown", withMaterials(R"({"m":{"type":"plastic"}})"), "/materials/m/type",
         "must be one of \"lambertian\", \"metal\", \"dielectric\", \"diffuse_light\" (got string \"plastic\")"},
        {"albedo_above_one", withMaterials(R"({"m":{"type":"lambertian","albedo":[1.5,0,0]}})"), "/materials/m/albedo/0",
         "must be in [0, 1] (got 1.5)"},
        {"albedo_missing", withMaterials(R"({"m":{"type":"metal"}})"), "/materials/m/albedo", "missing required key"},
        {"emit_negative", withMaterials(R"({"m":{"type":"lambertian","albedo":[1,1,1],"emit":[0,-1,0]}})"),
         "/materials/m/emit/1", "must be in [0, 4e+15] (got -1)"},
        {"emit_overflows", withMaterials(R"({"m":{"type":"diffuse_light","emit":[3e38,3e38,3e38]}})"), "/materials/m/emit/0",
         "must be in [0, 4e+15] (got 3e+38)"},
        {"light_emit_missing", withMaterials(R"({"m":{"type":"diffuse_light"}})"), "/materials/m/emit", "missing required key"},
        {"fuzz_range", withMaterials(R"({"m":{"type":"metal","albedo":[1,1,1],"fuzz":1.5}})"), "/materials/m/fuzz",
         "must be in [0, 1] (got 1.5)"},
        {"ior_zero", withMaterials(R"({"m":{"type":"dielectric","ior":0}})"), "/materials/m/ior", "must be > 0 (got 0)"},
        {"absorption_negative", withMaterials(R"({"m":{"type":"dielectric","ior":1.5,"absorption":[0,-1,0]}})"),
         "/materials/m/absorption/1", "must be in [0, 1e+30] (got -1)"},
        {"absorption_type", withMaterials(R"({"m":{"type":"dielectric","ior":1.5,"absorption":0.5}})"), "/materials/m/absorption",
         "must be an array"},
        {"fresnel_unknown", withMaterials(R"({"m":{"type":"dielectric","ior":1.5,"fresnel":"fast"}})"), "/materials/m/fresnel",
         "must be one of \"schlick\", \"exact\""},
        {"two_sided_type", withMaterials(R"({"m":{"type":"diffuse_light","emit":[1,1,1],"two_sided":"yes"}})"),
         "/materials/m/two_sided", "must be true or false"},
        {"key_of_other_type", withMaterials(R"({"m":{"type":"metal","albedo":[1,1,1],"emit":[1,1,1]}})"), "/materials/m/emit",
         "unknown key (allowed here: type, albedo, fuzz)"},
        {"material_name_escaped", withMaterials(R"({"a/b~c":{"type":"lambertian","albedo":[2,0,0]}})"),
         "/materials/a~1b~0c/albedo/0", "must be in [0, 1]"},
        // textures (scenes/README.md "Textures")
        {"texture_unknown_name", withMaterials(R"({"m":{"type":"lambertian","albedo":"wood"}})"), "/materials/m/albedo",
         "no texture named \"wood\" in /textures"},
        {"texture_kind_unknown", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"wood"}}})"),
         "/materials/m/albedo/type", "must be one of \"solid\", \"checker\", \"image\", \"noise\", \"turbulence\", \"marble\""},
        {"texture_not_object", withMaterials(R"({"m":{"type":"lambertian","albedo":3}})"), "/materials/m/albedo",
         "must be an object"},
        {"texture_colour_above_one", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"checker","scale":1,"even":[2,0,0],"odd":[1,1,1]}}})"),
         "/materials/m/albedo/even/0", "must be in [0, 1] (got 2)"},
        {"texture_emission_range", withMaterials(R"({"m":{"type":"diffuse_light","emit":{"type":"noise","color":[-1,0,0]}}})"),
         "/materials/m/emit/color/0", "must be in [0, 4e+15] (got -1)"},
        {"texture_scale_zero", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"checker","scale":0,"even":[0,0,0],"odd":[1,1,1]}}})"),
         "/materials/m/albedo/scale", "must be > 0 (got 0)"},
        {"texture_scale_tiny", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"checker","scale":1e-39,"even":[0,0,0],"odd":[1,1,1]}}})"),
         "/materials/m/albedo/scale", "is too small"},
        {"texture_noise_scale", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"marble","scale":-4}}})"),
         "/materials/m/albedo/scale", "must be > 0 (got -4)"},
        {"texture_unknown_key", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"noise","scale":4,"octaves":7}}})"),
         "/materials/m/albedo/octaves", "unknown key (allowed here: type, color, scale)"},
        {"texture_checker_side_missing", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"checker","scale":1,"even":[0,0,0]}}})"),
         "/materials/m/albedo/odd", "missing required key"},
        {"texture_cycle", scene(kCamera, R"({"m":{"type":"lambertian","albedo":"a"}})", "[" + kSphere + "]",
                                R"(,"textures":{"a":{"type":"checker","scale":1,"even":"b","odd":[0,0,0]},"b":{"type":"checker","scale":2,"even":[1,1,1],"odd":"a"}})"),
         "/textures/b/odd", "texture \"a\" refers to itself"},
        {"texture_nesting", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":{"type":"checker","scale":1,"even":[0,0,0],"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]},"odd":[1,1,1]}}})"),
         "/materials/m/albedo/even", "checkers nest more than 16 deep"},
        {"texture_unused_checked", scene(kCamera, kMaterials, "[" + kSphere + "]", R"(,"textures":{"spare":{"type":"noise","scale":-1}})"),
         "/textures/spare/scale", "must be > 0 (got -1)"},
        {"textures_not_object", scene(kCamera, kMaterials, "[" + kSphere + "]", R"(,"textures":[])"), "/textures",
         "must be an object"},
        {"texture_on_dielectric", withMaterials(R"({"m":{"type":"dielectric","ior":1.5,"albedo":{"type":"noise"}}})"),
         "/materials/m/albedo", "unknown key"},
        {"texture_image_missing_file", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"image","file":"no-such.png"}}})"),
         "/materials/m/albedo/file", "no-such.png"},
        {"texture_image_extension", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"image","file":"earth.bmp"}}})"),
         "/materials/m/albedo/file", "unknown image extension '.bmp'"},
        {"texture_image_outside", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"image","file":"../../etc/hostname.png"}}})"),
         "/materials/m/albedo/file", "outside"},
        {"texture_image_filter", withMaterials(R"({"m":{"type":"lambertian","albedo":{"type":"image","file":"a.png","filter":"cubic"}}})"),
         "/materials/m/albedo/filter", "must be one of \"linear\", \"nearest\""},
        // media (scenes/README.md "Media")
        {"medium_boundary_quad", withObject(R"({"type":"constant_medium","density":1,"albedo":[1,1,1],"boundary":{"type":"quad","Q":[0,0,0],"u":[1,0,0],"v":[0,1,0]}})"),
         "/objects/0/boundary/type", "a medium's boundary must be a \"sphere\" or a \"box\" (closed and convex), not a \"quad\""},
        {"medium_boundary_missing", withObject(R"({"type":"constant_medium","density":1,"albedo":[1,1,1]})"),
         "/objects/0/boundary", "missing required key"},
        {"medium_boundary_material", withObject(R"({"type":"constant_medium","density":1,"albedo":[1,1,1],"boundary":{"type":"sphere","center":[0,0,0],"radius":1,"material":"m"}})"),
         "/objects/0/boundary/material", "unknown key (allowed here: type, transform, center, radius)"},
        {"medium_density_zero", withObject(R"({"type":"constant_medium","density":0,"albedo":[1,1,1],"boundary":{"type":"sphere","center":[0,0,0],"radius":1}})"),
         "/objects/0/density", "must be > 0 (got 0)"},
        {"medium_density_underflow", withObject(R"({"type":"constant_medium","density":1e-60,"albedo":[1,1,1],"boundary":{"type":"sphere","center":[0,0,0],"radius":1}})"),
         "/objects/0/density", "must be a positive 32-bit float"},
        {"medium_albedo_range", withObject(R"({"type":"constant_medium","density":1,"albedo":[1.5,1,1],"boundary":{"type":"sphere","center":[0,0,0],"radius":1}})"),
         "/objects/0/albedo/0", "must be in [0, 1]"},
        {"medium_albedo_texture_unknown", withObject(R"({"type":"constant_medium","density":1,"albedo":"smoke","boundary":{"type":"sphere","center":[0,0,0],"radius":1}})"),
         "/objects/0/albedo", "no texture named \"smoke\" in /textures"},
        {"medium_box_inverted", withObject(R"({"type":"constant_medium","density":1,"albedo":[1,1,1],"boundary":{"type":"box","min":[0,0,0],"max":[1,-1,1]}})"),
         "/objects/0/boundary/max/1", "must be > min[1]"},
        {"medium_sphere_radius", withObject(R"({"type":"constant_medium","density":1,"albedo":[1,1,1],"boundary":{"type":"sphere","center":[0,0,0],"radius":0}})"),
         "/objects/0/boundary/radius", "must be > 0 (got 0)"},
        {"medium_material_key", withObject(R"({"type":"constant_medium","density":1,"albedo":[1,1,1],"material":"m","boundary":{"type":"sphere","center":[0,0,0],"radius":1}})"),
         "/objects/0/material", "unknown key (allowed here: type, boundary, density, albedo)"},
        {"medium_too_many", withObjects("[" + [] {
             std::string list;
             for (int i = 0; i < 65; ++i)
                 list += std::string(i ? "," : "") + R"({"type":"constant_medium","density":1,"albedo":[1,1,1],"boundary":{"type":"sphere","center":[0,0,0],"radius":1}})";
             return list;
         }() + "]"),
         "/objects/64", "too many media: at most 64"},
        // objects
        {"objects_type", withObjects("{}"), "/objects", "must be an array (got object"},
        {"object_type", withObjects("[" + kSphere + ",3]"), "/objects/1", "must be an object (got 3)"},
        {"object_kind_unknown", withObject(R"({"type":"cylinder","material":"m"})"), "/objects/0/type", "must be one of \"sphere\""},
        {"material_missing", withObject(R"({"type":"sphere","center":[0,0,0],"radius":1})"), "/objects/0/material",
         "missing required key"},
        {"material_unknown", withObjects("[" + kSphere + "," + kSphere + R"(,{"type":"sphere","center":[0,0,0],"radius":1,"material":"gold"}])"),
         "/objects/2/material", "unknown material \"gold\""},
        {"radius_negative", withObjects("[" + kSphere + "," + kSphere + "," + kSphere + R"(,{"type":"sphere","center":[0,0,0],"radius":-1,"material":"m"}])"),
         "/objects/3/radius", "must be > 0 (got -1)"},
        {"object_unknown_key", sphereWith(R"(,"radius":1,"colour":[1,0,0])"), "/objects/0/colour",
         "unknown key (allowed here: type, material, sample, transform, center, radius, center1, motion)"},
        {"sample_type", sphereWith(R"(,"radius":1,"sample":1)"), "/objects/0/sample", "must be true or false (got 1)"},
        {"sample_false_on_emitter", withObject(R"({"type":"sphere","center":[0,0,0],"radius":1,"material":"lamp","sample":false})"),
         "/objects/0/sample", "must not be false"},
        {"quad_u_zero", withObject(R"({"type":"quad","Q":[0,0,0],"u":[0,0,0],"v":[0,1,0],"material":"m"})"), "/objects/0/u",
         "must not be zero"},
        {"quad_parallel", withObject(R"({"type":"quad","Q":[0,0,0],"u":[1,2,3],"v":[-2,-4,-6],"material":"m"})"), "/objects/0/v",
         "must not be zero or parallel to u"},
        {"box_min_max", withObject(R"({"type":"box","min":[0,0,0],"max":[1,0,1],"material":"m"})"), "/objects/0/max/1",
         "must be > min[1] (got 0 <= 0)"},
        {"misspelt_center", withObject(R"({"type":"sphere","centre":[0,0,0],"radius":1,"material":"m"})"), "/objects/0/center",
         "missing required key (is \"centre\" a misspelling?)"},
        {"triangle_vertex_missing", withObject(R"({"type":"triangle","v0":[0,0,0],"v1":[1,0,0],"material":"m"})"),
         "/objects/0/v2", "missing required key"},
        {"zero_area_sampled", withObject(R"({"type":"triangle","v0":[0,0,0],"v1":[1,0,0],"v2":[2,0,0],"material":"m","sample":true})"),
         "/objects/0/sample", "a zero-area triangle cannot be sampled"},
        {"zero_area_emitter", withObject(R"({"type":"triangle","v0":[1,1,1],"v1":[1,1,1],"v2":[1,1,1],"material":"lamp"})"),
         "/objects/0/material", "a zero-area triangle cannot have an emitting material"},
        // transforms
        {"transform_type", sphereWith(R"(,"radius":1,"transform":{"scale":2})"), "/objects/0/transform", "must be an array"},
        {"transform_step_type", sphereWith(R"(,"radius":1,"transform":["scale"])"), "/objects/0/transform/0", "must be an object"},
        {"transform_two_keys", sphereWith(R"(,"radius":1,"transform":[{"scale":2,"rotate_y":3}])"), "/objects/0/transform/0",
         "must have exactly one key"},
        {"transform_unknown", sphereWith(R"(,"radius":1,"transform":[{"translate":[1,1,1]},{"rotate":30}])"),
         "/objects/0/transform/1/rotate", "unknown key (allowed here: translate, rotate_x, rotate_y, rotate_z, scale)"},
        {"rotate_type", sphereWith(R"(,"radius":1,"transform":[{"rotate_y":"15"}])"), "/objects/0/transform/0/rotate_y",
         "must be a number"},
        {"translate_type", sphereWith(R"(,"radius":1,"transform":[{"translate":5}])"), "/objects/0/transform/0/translate",
         "must be an array of 3 numbers"},
        {"scale_zero", sphereWith(R"(,"radius":1,"transform":[{"scale":0}])"), "/objects/0/transform/0/scale", "must not be 0"},
        {"scale_component_zero", withObject(R"({"type":"quad","Q":[0,0,0],"u":[1,0,0],"v":[0,1,0],"material":"m","transform":[{"scale":[1,0,1]}]})"),
         "/objects/0/transform/0/scale/1", "must not be 0"},
        {"sphere_non_uniform", sphereWith(R"(,"radius":1,"transform":[{"scale":2},{"scale":[1,2,1]}])"),
         "/objects/0/transform/1/scale", "a sphere cannot be scaled non-uniformly"},
        {"transform_overflow", sphereWith(R"(,"radius":1,"transform":[{"translate":[3e38,0,0]},{"translate":[3e38,0,0]}])"),
         "/objects/0", "does not fit 32-bit floats relative to the camera"},
        // Coordinates are read in double and made camera-relative: 1e39 is a valid JSON number,
        // but 1e39 from the camera is not a float.
        {"far_from_camera", withObject(R"({"type":"triangle","v0":[0,0,0],"v1":[1e39,0,0],"v2":[0,1,0],"material":"m"})"),
         "/objects/0", "the transformed triangle does not fit 32-bit floats relative to the camera"},
        // Inside float range, but a bounding box (and so the BVH's box centres) would overflow: named
        // by the object's pointer (not by a shape index: a box before it is 6 shapes) and said as it is.
        {"box_overflow", withObjects("[" + kSphere + R"(,{"type":"box","min":[0,0,0],"max":[1,1,1],"material":"m"},)" + kSphere + "," +
                                     kSphere + "," + kSphere + "," + kSphere +
                                     R"(,{"type":"sphere","center":[2e38,0,5],"radius":1,"material":"m"}])"),
         "/objects/6", "the sphere reaches 2e+38 from the camera: its coordinates overflow 32-bit floats"},
        {"quad_corner_overflow", withObject(R"({"type":"quad","Q":[9e37,0,0],"u":[9e37,0,0],"v":[0,1,0],"material":"m"})"),
         "/objects/0", "the quad reaches 1.8e+38 from the camera: its coordinates overflow"},
        // Motion blur: a sphere's "center1", any shape's "motion" (scenes/README.md "Motion blur").
        {"center1_type", sphereWith(R"(,"radius":1,"center1":[0,1])"), "/objects/0/center1", "must be an array of 3 numbers"},
        {"center1_on_quad", withObject(R"({"type":"quad","Q":[0,0,0],"u":[1,0,0],"v":[0,1,0],"center1":[0,1,0],"material":"m"})"),
         "/objects/0/center1", "unknown key"},
        {"motion_type", sphereWith(R"(,"radius":1,"motion":[0,1,0])"), "/objects/0/motion", "must be an object"},
        {"motion_no_translate", sphereWith(R"(,"radius":1,"motion":{})"), "/objects/0/motion/translate", "missing required key"},
        {"motion_unknown_key", sphereWith(R"(,"radius":1,"motion":{"translate":[0,1,0],"rotate_y":5})"), "/objects/0/motion/rotate_y",
         "unknown key (allowed here: translate)"},
        {"motion_element_type", withObject(R"({"type":"box","min":[0,0,0],"max":[1,1,1],"material":"m","motion":{"translate":[0,"1",0]}})"),
         "/objects/0/motion/translate/1", "must be a number"},
        {"motion_overflow", sphereWith(R"(,"radius":1,"motion":{"translate":[2e38,0,0]})"), "/objects/0/motion",
         "moves the sphere to 2e+38 from the camera: its coordinates overflow 32-bit floats"},
        {"motion_float_overflow", withObject(R"({"type":"triangle","v0":[0,0,0],"v1":[1,0,0],"v2":[0,1,0],"material":"m","motion":{"translate":[0,0,1e39]}})"),
         "/objects/0/motion", "the triangle's motion does not fit 32-bit floats"},
        {"center1_overflow", sphereWith(R"(,"radius":1,"center1":[0,-3e38,0])"), "/objects/0/center1",
         "moves the sphere to 3e+38 from the camera"},
        {"point_light_motion", withObject(R"({"type":"point_light","position":[0,2,0],"intensity":[1,1,1],"motion":{"translate":[1,0,0]}})"),
         "/objects/0/motion", "a point_light cannot move: motion blur moves shapes"},
        {"directional_light_motion",
         withObject(R"({"type":"directional_light","direction":[0,-1,0],"irradiance":[1,1,1],"motion":{"translate":[1,0,0]}})"),
         "/objects/0/motion", "a directional_light cannot move"},
        // environment (files relative to the scene's folder; none of these exist)
        {"env_type", withEnv("[]"), "/environment", "must be an object"},
        {"env_file_missing_key", withEnv(R"({"strength":1})"), "/environment/file", "missing required key"},
        {"env_file_type", withEnv(R"({"file":3})"), "/environment/file", "must be a string"},
        {"env_file_empty", withEnv(R"({"file":""})"), "/environment/file", "must not be empty"},
        {"env_file_absent", withEnv(R"({"file":"no-such-sky.hdr"})"), "/environment/file", "cannot use environment map"},
        {"env_file_png", withEnv(R"({"file":"sky.png"})"), "/environment/file", "PNG is display-encoded"},
        {"env_file_extension", withEnv(R"({"file":"sky.jpg"})"), "/environment/file", "unknown image extension"},
        {"env_strength_negative", withEnv(R"({"file":"sky.hdr","strength":-1})"), "/environment/strength", "must be >= 0 (got -1)"},
        {"env_rotate_type", withEnv(R"({"file":"sky.hdr","rotate_y":"90"})"), "/environment/rotate_y", "must be a number"},
        {"env_unknown_key", withEnv(R"({"file":"sky.hdr","rotate":90})"), "/environment/rotate", "unknown key"},
        {"env_and_background", scene(kCamera, kMaterials, "[" + kSphere + "]",
                                     R"(,"render":{"background":[1,1,1]},"environment":{"file":"sky.hdr"})"),
         "/environment", "cannot be combined with a non-zero render/background"},
    };
}

class SceneErrors : public ::testing::TestWithParam<Case> {};

TEST_P(SceneErrors, OneLineWithPointer) {
    const Case& c = GetParam();
    const std::filesystem::path file = vkp::test::scratchDir("scene_errors") / (std::string(c.name) + ".json");
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out << c.text;
    }
    try {
        (void)vkp::loadSceneJson(file);
        FAIL() << "accepted: " << c.text;
    } catch (const vkp::InputError& e) {
        const std::string what = e.what();
        const std::string head = file.string() + ": " + c.where;
        EXPECT_EQ(what.rfind(head, 0), 0u) << "expected to start with: " << head << "\n got: " << what;
        EXPECT_NE(what.find(c.fragment, head.size()), std::string::npos) << "expected: " << c.fragment << "\n got: " << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

INSTANTIATE_TEST_SUITE_P(Table, SceneErrors, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return std::string(p.param.name); });

/// An environment map that exists but is corrupt or holds negative radiance: one line at
/// /environment/file naming the map's problem.
TEST(SceneErrorsFile, BadEnvironmentMapContent) {
    const auto dir = vkp::test::scratchDir("scene_errors");
    {
        std::ofstream(dir / "corrupt.hdr", std::ios::binary | std::ios::trunc) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 4 +X";
        std::ofstream pfm(dir / "negative.pfm", std::ios::binary | std::ios::trunc);
        pfm << "PF\n1 1\n-1.0\n";
        const float px[3] = {1.0f, -2.0f, 0.5f};
        pfm.write(reinterpret_cast<const char*>(px), sizeof px);
    }
    for (const char* map : {"corrupt.hdr", "negative.pfm"}) {
        const auto file = dir / (std::string("env-") + map + ".json");
        std::ofstream(file, std::ios::binary | std::ios::trunc) << withEnv(std::string(R"({"file":")") + map + "\"}");
        try {
            (void)vkp::loadSceneJson(file);
            ADD_FAILURE() << "accepted " << map;
        } catch (const vkp::InputError& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind(file.string() + ": /environment/file: ", 0), 0u) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
            std::printf("  %s\n", what.c_str());
        }
    }
}

TEST(SceneErrorsFile, MissingFile) {
    const auto file = vkp::test::scratchDir("scene_errors") / "does-not-exist.json";
    std::filesystem::remove(file);
    try {
        (void)vkp::loadSceneJson(file);
        FAIL();
    } catch (const vkp::InputError& e) {
        EXPECT_EQ(std::string(e.what()), file.string() + ": cannot read: no such file");
    }
}

TEST(SceneErrorsFile, Directory) {
    const auto dir = vkp::test::scratchDir("scene_errors");
    try {
        (void)vkp::loadSceneJson(dir);
        FAIL();
    } catch (const vkp::InputError& e) {
        EXPECT_EQ(std::string(e.what()), dir.string() + ": cannot read: is a directory");
    }
}

TEST(SceneErrorsFile, MessageNamesTheFileAsGiven) {
    try {
        (void)vkp::parseSceneJson(withObject(R"({"type":"sphere","center":[0,0,0],"radius":-1,"material":"m"})"),
                                  "scenes/x.json");
        FAIL();
    } catch (const vkp::InputError& e) {
        EXPECT_STREQ(e.what(), "scenes/x.json: /objects/0/radius: must be > 0 (got -1)");
    }
}

TEST(SceneErrorsFile, NoMisspellingHintForDifferentKeys) {
    // "u" and "v" are one edit from "Q" but are keys of their own: no "misspelling" hint.
    try {
        (void)vkp::parseSceneJson(withObject(R"({"type":"quad","u":[1,0,0],"v":[0,1,0],"material":"m"})"), "q.json");
        FAIL();
    } catch (const vkp::InputError& e) {
        EXPECT_STREQ(e.what(), "q.json: /objects/0/Q: missing required key");
    }
}

TEST(SceneErrorsFile, ControlCharactersStayOnOneLine) {
    // A material name with an escaped newline appears in the message: it must not break the line.
    try {
        (void)vkp::parseSceneJson(withMaterials(R"({"a\nb":{"type":"lambertian","albedo":[2,0,0]}})"), "x.json");
        FAIL();
    } catch (const vkp::InputError& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        EXPECT_EQ(what.rfind("x.json: /materials/a b/albedo/0: must be in [0, 1]", 0), 0u) << what;
    }
}

}  // namespace
