#version 460
// The distance field's second pass, for the voxels sdf_seed left without an exact answer (none
// of their brick's triangles within a brick of them): the nearest of their seed and their
// brick's far candidates (FieldGeometry::farCandidates: the triangles nearest to the centres of
// the brick and its 26 neighbours, jump flooded over the bricks on the CPU), each measured
// exactly. One pass in place of jump flooding over every voxel; a workgroup is one brick, so its
// invocations walk the same list.
#include "sdf_build.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

void main() {
    ivec3 v = slabVoxel();
    if (!insideField(v)) return;
    vec3 p = voxelCentre(v);
    uint best = imageLoad(idsIn, v).x;
    float bestDistance = best == FIELD_NO_TRIANGLE ? 3.4e38 : distanceTo(best, p);
    // Within a brick of its surface a voxel's seed is exact already (sdf_seed; a slab is at most
    // its thickness nearer than its triangle).
    if (bestDistance > float(FIELD_BRICK) * push.origin.w - push.thickness.x) {
        uint brick = brickOf(v);
        for (uint i = farCandidates[brick]; i < farCandidates[brick + 1u]; ++i) {
            uint id = farCandidates[i];
            float d = distanceTo(id, p);
            if (d < bestDistance) {
                bestDistance = d;
                best = id;
            }
        }
    }
    imageStore(idsOut, v, uvec4(best));
}
