#version 460
// The distance field's last pass, one invocation per column of voxels along z (a slab of rows
// from FieldPush.size.w on y): each voxel's distance to its nearest triangle (open geometry less
// its thickness), negative inside closed surfaces. Inside is decided by the winding number along
// the column from below: the closed triangles it crosses under the voxel's centre, +1 entering,
// -1 leaving (columnCrossing). The bricks' lists hold every triangle that crosses a brick, and
// each crossing is counted in the brick that holds its z, so every crossing counts once; each
// brick's list is read once per column.
#include "sdf_build.glsl"
layout(local_size_x = 8, local_size_y = 8) in;

void main() {
    ivec2 xy = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, int(push.size.w));
    if (any(greaterThanEqual(uvec2(xy), push.size.xy))) return;
    float voxel = push.origin.w;
    vec2 column = voxelCentre(ivec3(xy, 0)).xy;
    int below = 0; // winding of the bricks under the current one
    for (int z0 = 0; z0 < int(push.size.z); z0 += int(FIELD_BRICK)) {
        uint brick = brickOf(ivec3(xy, z0));
        float brickFloor = push.origin.z + float(z0) * voxel;
        float brickTop = push.origin.z + float(z0 + int(FIELD_BRICK)) * voxel;
        int winding[FIELD_BRICK]; // the brick's crossings under each of its voxels' centres
        for (int k = 0; k < int(FIELD_BRICK); ++k) winding[k] = 0;
        int through = 0; // all of the brick's crossings
        for (uint i = brickStarts[brick]; i < brickStarts[brick + 1u]; ++i) {
            uint id = brickList[i];
            uint flags = triangleFlags(id);
            if ((flags & FIELD_OPEN) != 0u) continue;
            FieldTriangle t = triangles[id];
            float z;
            int crossing = columnCrossing(column, t.a.xyz, t.b.xyz, t.c.xyz, z);
            if (crossing == 0 || z < brickFloor || z >= brickTop) continue;
            crossing = (flags & FIELD_FLIPPED) != 0u ? -crossing : crossing;
            through += crossing;
            for (int k = 0; k < int(FIELD_BRICK); ++k)
                if (z < voxelCentre(ivec3(xy, z0 + k)).z) winding[k] += crossing;
        }
        for (int k = 0; k < int(FIELD_BRICK); ++k) {
            ivec3 v = ivec3(xy, z0 + k);
            uint id = imageLoad(idsIn, v).x;
            float d = id == FIELD_NO_TRIANGLE ? 3.4e38 : distanceTo(id, voxelCentre(v));
            imageStore(field, v, vec4(below + winding[k] > 0 ? -abs(d) : d));
        }
        below += through;
    }
}
