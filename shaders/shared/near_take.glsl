// A SIMD row's draw from the near list when the rows take them (near_raster.h, kTakeDraws): one
// atomic per row on NearTaken's counter `counter`, the slot handed to all its lanes. Shared by
// near_vertices.comp and near_raster.comp, which declare NearTaken { uint nearTaken[2]; } first.
// Needs GL_KHR_shader_subgroup_ballot.
#ifndef MEADOW_NEAR_TAKE_GLSL
#define MEADOW_NEAR_TAKE_GLSL

uint nearTakeSlot(uint counter) {
    uint slot = 0u;
    if (subgroupElect())
        slot = atomicAdd(nearTaken[counter], 1u);
    return subgroupBroadcastFirst(slot);
}

// Where a workgroup's threads start on the list and on a draw's vertices or triangles: with the
// rows taking draws, each row's first slot (taken), its lanes striding by the row's width; dealt in
// turn, the workgroup's first slot, its threads striding by the workgroup's width. A row past the
// last slot draws nothing.
struct NearShare {
    uint item;  // the list slot (spread by workEntry)
    uint lane;  // this thread's first vertex or triangle
    uint width; // the stride over them
    uint rows;  // taken: SIMD rows in the dispatch (a row takes another draw only when there are more)
};

NearShare nearShareStart(bool take, uint counter) {
    NearShare s;
    if (take) {
        s.item = nearTakeSlot(counter);
        s.lane = gl_SubgroupInvocationID;
        s.width = subgroupBallotBitCount(subgroupBallot(true));
        s.rows = gl_NumWorkGroups.x * gl_NumSubgroups;
    } else {
        s.item = gl_WorkGroupID.x;
        s.lane = gl_LocalInvocationID.x;
        s.width = gl_WorkGroupSize.x;
        s.rows = 0u;
    }
    return s;
}

// The next slot for the same threads, or one past the list's `total` when they are done: dealt, every
// gl_NumWorkGroups-th; taken, another only when the list is longer than the dispatch has rows (over
// kNearMaxGroups workgroups), else the row's one draw was its share.
uint nearShareNext(bool take, uint counter, NearShare s, uint total) {
    if (take)
        return total > s.rows ? nearTakeSlot(counter) : total;
    return s.item + gl_NumWorkGroups.x;
}

#endif
