// The grid that temporal_filters.glsl's reconstructInterleaved reads, staged in shared memory: each
// workgroup copies the grid pixels its gathers reach (its own and kGridTileReach around: 2 for the 5x5 and
// 4x4 windows, 1 for the 2x2 ones) into shared memory once, and the taps of each pixel read them there
// instead of (depth, normal, values) global loads per tap. The values are the same floats, so the filter's
// result is unchanged.
//
// reconstruct_interleaved.comp uses it, and gtao_temporal.comp where it runs the same reconstruction inside
// the accumulation (at full resolution, and on the grid with the grid's history) with the 5x5 and 4x4
// windows; there the 2x2 windows read their 4 taps from memory. The half-resolution accumulation with the
// history at full resolution upsamples, reads 4 grid pixels and declares a tile of 1 slot: on an H100
// (2026-11-25) the full tile's shared memory alone, never filled, made that variant 1.8x slower (fewer
// workgroups per SM).
//
// The including shader declares, before the #include, the grid in global memory:
//   kGridChannels, float gridDepthAt(int x, int y), vec3 gridNormalAt(int x, int y),
//   float gridValueAt(int x, int y, int c)
// and calls loadGridTile(width, height) from every invocation of the workgroup (it holds a barrier), before
// any invocation returns. Then gridTileDepth, gridTileNormal and gridTileValue read the tile; they may be
// asked only for pixels within kGridTileReach of the workgroup's own (all that the reconstruction reads).
// Outside the grid gridTileDepth is +inf (and the others the edge's), so an includer whose filter reads the
// tile defines GRID_OUTSIDE_IS_SKY true. The includer's gridDepth, gridNormal and gridValue
// (temporal_filters.glsl's grid) call them.
#ifndef OBSCURA_GPU_GRID_TILE_GLSL
#define OBSCURA_GPU_GRID_TILE_GLSL

// How far the reconstruction's taps reach: 2 for the 5x5 and 4x4 windows. An including shader whose window
// reaches less defines GRID_TILE_REACH as an expression of its specialization constants: the 2x2 windows
// (obscura/reconstruct_window.h) reach 1, and their tile is then 34x6 slots instead of 36x8 (32x4
// workgroups), 29% fewer loads of depth, normal and values for the same taps.
#ifndef GRID_TILE_REACH
#define GRID_TILE_REACH 2
#endif
const int kGridTileReach = GRID_TILE_REACH;
const int kGridTileWidth = kAccumulationWorkgroupX + 2 * kGridTileReach;
const int kGridTileHeight = kAccumulationWorkgroupY + 2 * kGridTileReach;
// Rows packed. With 8x8 workgroups, rows 24 floats apart (a warp's 4 rows of 8 reads in 32 different banks)
// were no faster on an H100 (2026-11-25) and took twice the shared memory.
const int kGridTileStride = kGridTileWidth;
// An including shader that fills the tile only in some variants defines GRID_TILE_SLOTS as an expression of
// its specialization constants that is 1 in the others: shared memory that is declared costs occupancy
// whether or not it is used.
#ifndef GRID_TILE_SLOTS
#define GRID_TILE_SLOTS (kGridTileHeight * kGridTileStride)
#endif
shared float tileDepth[GRID_TILE_SLOTS];
shared float tileNormal[3][GRID_TILE_SLOTS];
shared float tileValue[4][GRID_TILE_SLOTS];
ivec2 tileOrigin;  // the grid pixel at tile (0, 0)

void loadGridTile(int width, int height) {
    tileOrigin = ivec2(gl_WorkGroupID.xy) * ivec2(kAccumulationWorkgroupX, kAccumulationWorkgroupY) - kGridTileReach;
    const int first = int(gl_LocalInvocationID.y) * kAccumulationWorkgroupX + int(gl_LocalInvocationID.x);
    for (int t = first; t < kGridTileWidth * kGridTileHeight; t += kAccumulationWorkgroupX * kAccumulationWorkgroupY) {
        const int tx = t % kGridTileWidth, ty = t / kGridTileWidth;
        // Slots outside the grid repeat the edge, so that every load is in bounds, with an infinite depth:
        // the reconstruction skips them as sky (GRID_OUTSIDE_IS_SKY), as the CPU skips taps outside the image.
        const int ux = tileOrigin.x + tx, uy = tileOrigin.y + ty;
        const int x = clamp(ux, 0, width - 1), y = clamp(uy, 0, height - 1);
        const int s = ty * kGridTileStride + tx;
        tileDepth[s] = x == ux && y == uy ? gridDepthAt(x, y) : uintBitsToFloat(0x7f800000u);
        const vec3 n = gridNormalAt(x, y);
        tileNormal[0][s] = n.x;
        tileNormal[1][s] = n.y;
        tileNormal[2][s] = n.z;
        for (int c = 0; c < kGridChannels; ++c) tileValue[c][s] = gridValueAt(x, y, c);
    }
    barrier();
}

int tileIndex(int x, int y) { return (y - tileOrigin.y) * kGridTileStride + (x - tileOrigin.x); }
float gridTileDepth(int x, int y) { return tileDepth[tileIndex(x, y)]; }
vec3 gridTileNormal(int x, int y) {
    const int s = tileIndex(x, y);
    return vec3(tileNormal[0][s], tileNormal[1][s], tileNormal[2][s]);
}
float gridTileValue(int x, int y, int c) { return tileValue[c][tileIndex(x, y)]; }

#endif
