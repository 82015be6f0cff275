// A top-level leaf primitive p, for both BVH layouts (the kernels' 4-wide lib/traverse_wide.glsl and
// the layout benchmark's binary shaders/tests/traverse_binary.glsl): with VKP_HAS_INSTANCES, a
// PRIM_INSTANCE maps the ray into its object space (the direction not renormalised, so t is shared)
// and traverses its mesh's bottom level from its root in this layout (+1 pass: that loop's exit);
// anything else is an ordinary leaf test (lib/leaf_test.glsl). Included once per layout with
//   VKP_TOP_LEAF_FN        the function's name
//   VKP_BOTTOM_LOOP_FN     that layout's bottom-level loop (lib/traverse_wide_loop.glsl,
//                          tests/traverse_binary_loop.glsl)
//   VKP_INSTANCE_ROOT(ins) the instance's root in that layout (shared/instance.h: info.x 4-wide, info.y binary)
bool VKP_TOP_LEAF_FN(const bool anyHit, uint p, vec3 o, vec3 d, float tmin, inout float t, inout uint primIndex,
                     inout vec2 abHit, inout uint inst, inout uint passes) {
    if (VKP_HAS_INSTANCES) {
        GpuPrim pr = fetchPrim(p);
        if (primKind(pr) == PRIM_INSTANCE) {
            uint id = primMaterial(pr);
            GpuInstance ins = fetchInstance(id);
            passes += 1u;
            return VKP_BOTTOM_LOOP_FN(anyHit, VKP_INSTANCE_ROOT(ins), instanceRayOrigin(ins, o), instanceRayDirection(ins, d),
                                      tmin, t, primIndex, abHit, inst, id, passes);
        }
    }
    return vkpLeafHitInstance(p, o, d, tmin, t, primIndex, abHit, inst, GPU_NO_INSTANCE);
}
