#pragma once
// A 3D scene's tree from OctoMap (octomap::OcTree; .bt and .ot files): the
// octree follows OctoMap's own subdivision, its leaves are OctoMap's
// occupied leaves (isNodeOccupied), each an axis-aligned cube, including
// the coarser cubes OctoMap keeps where it pruned eight equal children.
// Free and unknown space are not stored. An internal node's bounds are the
// tight bounds of the occupied cubes below it.
//
// The answer is "does the OBB overlap the union of the occupied leaf
// cubes", exactly what testing every occupied leaf answers.
// Build: O(n log n) for n occupied leaves (a sort by Morton key).
#include <string>
#include <vector>

#include "robocore/collision/box_tree.h"

namespace octomap {
class OcTree;
}

namespace rc {

// The occupied leaves as boxes: centre from the leaf's key at its depth
// (OcTree::keyToCoord, in double), half = node size / 2.
std::vector<Aabbd> OccupiedLeafBoxes(const octomap::OcTree& tree);

BoxTree BuildOctreeFromOctoMap(const octomap::OcTree& tree);

// Reads a .bt (binary) or .ot (full) OctoMap file holding an OcTree and
// builds its tree. Throws InputError naming the file on failure.
BoxTree LoadOctoMapFile(const std::string& path);

}  // namespace rc
