// A light's shadow views as a per-light dispatch reads them (visibility.comp, translucent.comp):
// the including pass declares `views` (ShadowViewData[]), `push` (VisibilityPush: the light's
// first view in light.w), `frame` and the specialization constant LIGHT_VIEWS. Lavapipe loads a
// uniform record one lane at a time unless its index is uniform: the loops unroll and only pick.
#ifndef PENUMBRA_LIGHT_VIEWS_GLSL
#define PENUMBRA_LIGHT_VIEWS_GLSL

// View k of the dispatch's light (k < LIGHT_VIEWS; the first view otherwise).
ShadowViewData viewOf(uint k) {
    ShadowViewData view = views[push.light.w];
    for (uint j = 1u; j < LIGHT_VIEWS; ++j)
        if (k == j) view = views[push.light.w + j];
    return view;
}

// A sun's cascade for a point at camera view distance z: the first whose slice reaches it.
uint sunCascadeOf(float z) {
    uint i = 0u;
    bool further = true;
    for (uint j = 0u; j + 1u < LIGHT_VIEWS; ++j) {
        further = further && z > views[push.light.w + j].cascade.x;
        i += further ? 1u : 0u;
    }
    return i;
}

// The camera view distance of a world point (what splits a sun's cascades).
float cameraViewDistance(vec3 world) {
    return dot(world - frame.position.xyz, frame.cameraForward.xyz);
}

#endif
