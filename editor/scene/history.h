#pragma once
// Undo and redo as a stack of states ("mementos"): each step holds the state from before the change
// and a label ("move point", "import teapot.bpt"). Undo hands back the state before the latest step
// and keeps the current one for redo; redo the reverse. A new step clears the redo stack.
//
// Merging: between beginMerge() and endMerge() (one continuous drag, one grab) only the first change
// records a step; the later ones belong to it, so one undo takes the whole drag back. The history
// keeps at most limit() steps and drops the oldest beyond that.
//
// Invariants: size() <= limit(); redoSize() == 0 right after record(); while merging, at most one
// step is recorded. State is any copyable value (the Scene's is SceneState, tests use ints).

#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <utility>

namespace freeform::editor {

template <typename State>
class History {
public:
    explicit History(std::size_t limit = 1000) : limit_(limit < 1 ? 1 : limit) {}

    /// True when a change now records a step (false inside a merge that already has one). Callers
    /// check it before taking a snapshot, which may be expensive.
    bool wantsStep() const { return !(merging_ && mergeRecorded_); }

    /// Records a step: `before` is the state the change starts from.
    void record(std::string label, State before)
    {
        if (!wantsStep()) return;
        undo_.push_back({std::move(label), std::move(before)});
        redo_.clear();
        if (merging_) mergeRecorded_ = true;
        while (undo_.size() > limit_) undo_.pop_front();
    }

    void beginMerge()
    {
        merging_ = true;
        mergeRecorded_ = false;
    }
    /// Ends a merge; true when it recorded a step.
    bool endMerge()
    {
        const bool recorded = merging_ && mergeRecorded_;
        merging_ = mergeRecorded_ = false;
        return recorded;
    }
    bool merging() const { return merging_; }
    /// Ends the merge and removes its step without a redo entry; returns the state before it (to be
    /// restored by the caller), or nothing when the merge recorded no step.
    std::optional<State> cancelMerge()
    {
        const bool recorded = endMerge();
        if (!recorded || undo_.empty()) return std::nullopt;
        State before = std::move(undo_.back().state);
        undo_.pop_back();
        return before;
    }

    bool canUndo() const { return !undo_.empty(); }
    bool canRedo() const { return !redo_.empty(); }
    const std::string& undoLabel() const { return undo_.empty() ? none() : undo_.back().label; }
    const std::string& redoLabel() const { return redo_.empty() ? none() : redo_.back().label; }

    /// Takes the latest step back: returns the state to restore; `current` is kept for redo.
    std::optional<State> undo(State current)
    {
        if (undo_.empty()) return std::nullopt;
        merging_ = mergeRecorded_ = false;
        Step step = std::move(undo_.back());
        undo_.pop_back();
        redo_.push_back({step.label, std::move(current)});
        return std::move(step.state);
    }
    /// Does the latest undone step again: returns the state to restore; `current` goes to undo.
    std::optional<State> redo(State current)
    {
        if (redo_.empty()) return std::nullopt;
        merging_ = mergeRecorded_ = false;
        Step step = std::move(redo_.back());
        redo_.pop_back();
        undo_.push_back({step.label, std::move(current)});
        return std::move(step.state);
    }

    std::size_t size() const { return undo_.size(); }
    std::size_t redoSize() const { return redo_.size(); }
    std::size_t limit() const { return limit_; }
    void clear()
    {
        undo_.clear();
        redo_.clear();
        merging_ = mergeRecorded_ = false;
    }

private:
    struct Step {
        std::string label;
        State state;
    };
    static const std::string& none()
    {
        static const std::string empty;
        return empty;
    }

    std::deque<Step> undo_, redo_;
    std::size_t limit_;
    bool merging_ = false, mergeRecorded_ = false;
};

} // namespace freeform::editor
