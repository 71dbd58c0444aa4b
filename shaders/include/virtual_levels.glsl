// Virtual maps (virtual.enabled): which level of a light's virtual map a pixel reads, shared by
// the page marking (page_marking.comp) and the visibility pass, so that the pages asked for are
// the pages read. The including pass declares the frame block as `frame`, the view records as
// `views` and LIGHT_TYPE_OF.
#ifndef PENUMBRA_VIRTUAL_LEVELS_GLSL
#define PENUMBRA_VIRTUAL_LEVELS_GLSL
#include "light_geometry.h"
#include "virtual_pages.h"

// A light's levels a receiver may read (views first .. first + count - 1, finest first) and the
// one it wants: a sun's clipmap levels, or the mips of a spot's frustum or of the point light's
// cube face that holds it.
struct VirtualChoice {
    uint first, count, level;
};

// The world size of pixel p's neighbour step at the same depth (the pixel's footprint across the
// camera's ray).
float pixelWorldSize(ivec2 p, float depth, vec3 world) {
    return length(worldPosition(frame.invViewProj, p + ivec2(1, 0), frame.imageSize.xy, depth) -
                  world);
}

VirtualChoice virtualChoice(LightData light, vec3 world, float pixelWorld) {
    VirtualChoice c;
    c.first = light.views.x;
    c.count = light.views.y;
    if (LIGHT_TYPE_OF(light) != LIGHT_DIRECTIONAL) {
        c.count = frame.virtualPages.z;
        if (LIGHT_TYPE_OF(light) == LIGHT_POINT)
            c.first += cubeFace(world - light.positionType.xyz) * c.count;
    }
    ShadowViewData finest = views[c.first];
    float texel0 = finest.texel.x;
    if (finest.texel.y > 0.5) texel0 *= max((finest.shadowMatrix * vec4(world, 1.0)).w, 0.0);
    c.level = virtualLevelFor(pixelWorld, texel0, frame.virtualLod.x, c.count);
    return c;
}

// A level's side in texels.
uint virtualSize(ShadowViewData level) {
    return uint(level.cascade.w) * frame.virtualPages.x;
}

#endif
