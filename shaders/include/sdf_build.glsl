// What the distance field's build passes share (src/render/distance_field.h): the triangles, the
// bricks' triangle lists, the nearest-triangle ids and the field, bound the same way in each.
#ifndef PENUMBRA_SDF_BUILD_GLSL
#define PENUMBRA_SDF_BUILD_GLSL
#include "bindings.h"
#include "pass_types.h"
#include "sdf_math.h"

layout(set = 0, binding = FIELD_TRIANGLES, std430) readonly buffer Triangles {
    FieldTriangle triangles[];
};
layout(set = 0, binding = FIELD_BRICK_STARTS, std430) readonly buffer BrickStarts {
    uint brickStarts[];
};
layout(set = 0, binding = FIELD_BRICK_LIST, std430) readonly buffer BrickList { uint brickList[]; };
layout(set = 0, binding = FIELD_FAR_CANDIDATES, std430) readonly buffer FarCandidates {
    uint farCandidates[]; // bricks + 1 offsets into farCandidates, then the lists
};
layout(set = 0, binding = FIELD_IDS_IN, r32ui) uniform readonly uimage3D idsIn;
layout(set = 0, binding = FIELD_IDS_OUT, r32ui) uniform writeonly uimage3D idsOut;
layout(set = 0, binding = FIELD_OUT, r32f) uniform writeonly image3D field;
layout(push_constant) uniform Push { FieldPush push; };

vec3 voxelCentre(ivec3 v) { return push.origin.xyz + (vec3(v) + 0.5) * push.origin.w; }

// This invocation's voxel: the dispatch covers a slab of z from FieldPush.size.w.
ivec3 slabVoxel() { return ivec3(gl_GlobalInvocationID) + ivec3(0, 0, int(push.size.w)); }

bool insideField(ivec3 v) {
    return all(greaterThanEqual(v, ivec3(0))) && all(lessThan(uvec3(v), push.size.xyz));
}

uint brickOf(ivec3 v) {
    uvec3 bricks = push.size.xyz / FIELD_BRICK;
    uvec3 b = uvec3(v) / FIELD_BRICK;
    return (b.z * bricks.y + b.y) * bricks.x + b.x;
}

uint triangleFlags(uint id) { return floatBitsToUint(triangles[id].a.w); }

// The distance the build minimises: to the triangle, less the thickness of open geometry.
float distanceTo(uint id, vec3 p) {
    FieldTriangle t = triangles[id];
    return fieldTriangleDistance(p, t.a.xyz, t.b.xyz, t.c.xyz, floatBitsToUint(t.a.w),
                                 push.thickness.x);
}

#endif
