#version 460
// The distance field's second pass, for the voxels sdf_seed left without an exact answer (none
// of their brick's triangles within a brick of them): the nearest of their seed and the
// triangles nearest to the centres of their brick and its 26 neighbours (FieldGeometry's
// brickNearest, jump flooded over the bricks on the CPU), each measured exactly. One pass in
// place of jump flooding over every voxel.
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
    if (bestDistance <= float(FIELD_BRICK) * push.origin.w - push.thickness.x) {
        imageStore(idsOut, v, uvec4(best));
        return;
    }
    ivec3 bricks = ivec3(push.size.xyz / FIELD_BRICK);
    ivec3 home = v / int(FIELD_BRICK);
    uint tried[4] = uint[4](best, best, best, best); // neighbours mostly share a few ids
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                ivec3 b = home + ivec3(x, y, z);
                if (any(lessThan(b, ivec3(0))) || any(greaterThanEqual(b, bricks))) continue;
                uint id = brickNearest[(b.z * bricks.y + b.y) * bricks.x + b.x];
                if (id == FIELD_NO_TRIANGLE || id == tried[0] || id == tried[1] ||
                    id == tried[2] || id == tried[3])
                    continue;
                tried[3] = tried[2];
                tried[2] = tried[1];
                tried[1] = tried[0];
                tried[0] = id;
                float d = distanceTo(id, p);
                if (d < bestDistance) {
                    bestDistance = d;
                    best = id;
                }
            }
    imageStore(idsOut, v, uvec4(best));
}
