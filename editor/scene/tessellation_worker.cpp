#include "scene/tessellation_worker.h"

#include <exception>

namespace freeform::editor {

TessellationWorker::TessellationWorker() : thread_([this](std::stop_token stop) { run(stop); }) {}

TessellationWorker::~TessellationWorker()
{
    thread_.request_stop(); // wakes the waits below (condition_variable_any with the stop token)
    if (thread_.joinable()) thread_.join();
}

void TessellationWorker::submit(TessellationJob job)
{
    std::lock_guard lock(mutex_);
    latest_ = job.generation;
    done_.reset();
    if (job.items.empty()) queued_.reset();
    else queued_ = std::move(job);
    changed_.notify_all();
}

std::optional<TessellationResult> TessellationWorker::take()
{
    std::lock_guard lock(mutex_);
    std::optional<TessellationResult> out = std::move(done_);
    done_.reset();
    return out;
}

void TessellationWorker::wait()
{
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return !queued_ && !running_; });
}

void TessellationWorker::setHold(bool hold)
{
    std::lock_guard lock(mutex_);
    hold_ = hold;
    changed_.notify_all();
}

void TessellationWorker::waitUntilHeld()
{
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return held_; });
}

void TessellationWorker::run(std::stop_token stop)
{
    std::unique_lock lock(mutex_);
    for (;;) {
        if (!changed_.wait(lock, stop, [&] { return queued_.has_value(); })) return; // stop requested
        TessellationJob job = std::move(*queued_);
        queued_.reset();
        running_ = true;
        const long generation = job.generation;
        lock.unlock();

        TessellationResult result;
        result.generation = generation;
        result.tolerance = job.tolerance;
        result.items.reserve(job.items.size());
        bool superseded = false;
        for (TessellationJob::Item& item : job.items) {
            {
                std::lock_guard check(mutex_);
                superseded = latest_ != generation;
            }
            if (superseded || stop.stop_requested()) break;
            ItemGeometry g;
            try {
                g = item.object ? buildGeometry(*item.object, item.settings, job.tolerance, job.view)
                                : invalidGeometry(item.data, item.invalid, job.directory);
            } catch (const std::exception& e) { // buildGeometry reports Error in g.error itself
                g = ItemGeometry{};
                g.error = e.what();
            }
            result.items.push_back({item.id, item.key, std::move(g)});
        }

        lock.lock();
        if (!superseded && !stop.stop_requested()) {
            held_ = hold_;
            if (held_) changed_.notify_all();
            changed_.wait(lock, stop, [&] { return !hold_; });
            held_ = false;
            if (latest_ == generation) done_ = std::move(result);
        }
        running_ = false;
        changed_.notify_all();
        if (stop.stop_requested()) return;
    }
}

} // namespace freeform::editor
