#version 460
// The distance field's first pass: each voxel's nearest triangle among its brick's list (every
// triangle within a brick of it), exact wherever the nearest one is that close; FIELD_NO_TRIANGLE
// where the list is empty. sdf_flood gives the rest theirs.
#include "sdf_build.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

void main() {
    ivec3 v = slabVoxel();
    if (!insideField(v)) return;
    vec3 p = voxelCentre(v);
    uint brick = brickOf(v);
    uint best = FIELD_NO_TRIANGLE;
    float bestDistance = 3.4e38;
    for (uint i = brickStarts[brick]; i < brickStarts[brick + 1u]; ++i) {
        uint id = brickList[i];
        float d = distanceTo(id, p);
        if (d < bestDistance) {
            bestDistance = d;
            best = id;
        }
    }
    imageStore(idsOut, v, uvec4(best));
}
