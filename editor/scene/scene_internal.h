#pragma once
// What scene.cpp and scene_io.cpp share (private to editor/scene): the counters that make
// revisions, content keys and item ids unique across all scenes. One definition each, in
// scene.cpp, so that the two files draw from the same counters.

namespace freeform::editor::scene_detail {

/// Revisions are unique across all scenes, so a drawer never mistakes a new item for an old one.
int nextRevision();

/// Content keys are unique across all scenes too.
long nextKey();

/// Stable item ids, never reused (unique across all scenes, so a drawer or a tool that kept one
/// never finds another item under it).
long nextId();

} // namespace freeform::editor::scene_detail
