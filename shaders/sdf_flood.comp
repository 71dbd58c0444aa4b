#version 460
// One round of jump flooding [Rong and Tan 2006] over the nearest-triangle ids: each voxel keeps
// the nearest of its own triangle and those of the 26 voxels FieldPush.size.w away, measured
// exactly from its centre. Rounds at steps n/2, n/4, ..., 1, then 1 again, carry the seeds' ids
// across the whole field.
#include "sdf_build.glsl"
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

void main() {
    ivec3 v = ivec3(gl_GlobalInvocationID);
    if (!insideField(v)) return;
    vec3 p = voxelCentre(v);
    int step = int(push.size.w);
    uint best = imageLoad(idsIn, v).x;
    float bestDistance = best == FIELD_NO_TRIANGLE ? 3.4e38 : distanceTo(best, p);
    // Within a brick of its surface a voxel's seed is exact already (sdf_seed).
    if (bestDistance <= float(FIELD_BRICK) * push.origin.w) {
        imageStore(idsOut, v, uvec4(best));
        return;
    }
    uint tried = best; // neighbours often share an id: measure each run of them once
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                ivec3 q = v + step * ivec3(x, y, z);
                if ((x == 0 && y == 0 && z == 0) || !insideField(q)) continue;
                uint id = imageLoad(idsIn, q).x;
                if (id == FIELD_NO_TRIANGLE || id == tried) continue;
                tried = id;
                float d = distanceTo(id, p);
                if (d < bestDistance) {
                    bestDistance = d;
                    best = id;
                }
            }
    imageStore(idsOut, v, uvec4(best));
}
