#pragma once
// Background tessellation (docs/editor.md, "Tessellation to the view"): one worker thread that
// builds the geometry of scene items from copies of their data, so that a zoom which changes the
// view's tolerance does not stall the frames. The scene (scene/scene.h) submits a job, the items
// whose geometry was built for another tolerance, keeps drawing their old geometry meanwhile, and
// takes the result on the main thread, where it is applied only to items whose content key is
// still the one the job copied (an edit made meanwhile gives the item a new key, so a stale result
// is never shown). The GPU upload happens later, on the main thread, when the drawer sees the
// item's new revision.
//
// A new job supersedes the one queued or running: the running one stops before its next item and
// its result is dropped, never published. At most one result waits to be taken (the latest job's).
//
// Thread safety: a job owns copies of everything it reads (the typed object, or an invalid
// object's data and error, settings, the document's folder for relative cage paths); buildGeometry
// reads nothing shared (a subdivision surface's copy shares its immutable topology). The library's tessellation
// is reentrant on const geometry: it has no mutable statics (OpenSubdiv's error text is
// thread_local and its callback is installed once under std::call_once). The queue, the result
// and the hold below are guarded by one mutex.

#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "scene/scene.h"

namespace freeform::editor {

/// What a job builds: item copies, the tolerance, and the document folder for cage files.
struct TessellationJob {
    struct Item {
        long id = 0;          // SceneItem::id
        long key = 0;         // SceneItem::key when copied
        std::optional<TypedObject> object; // a copy of the item's typed object (Scene::typed)
        ObjectData data;      // else: a copy of the invalid object's data,
        std::string invalid;  // and why it is invalid (SceneItem::invalid)
        ObjectSettings settings;
    };
    long generation = 0;      // > 0, increasing with every job a scene submits
    double tolerance = 0;     // the world tolerance (buildGeometry's argument)
    PixelScale view;          // the view's pixel scale, for per-patch tolerances (buildGeometry's)
    std::string directory;    // Scene::documentDirectory()
    std::vector<Item> items;
};

/// The geometry a job built, in its items' order.
struct TessellationResult {
    struct Item {
        long id = 0, key = 0; // as in the job
        ItemGeometry geometry;
    };
    long generation = 0;
    double tolerance = 0;
    std::vector<Item> items;
};

class TessellationWorker {
public:
    TessellationWorker();
    /// Asks the thread to stop (a running job stops before its next item), then joins it.
    ~TessellationWorker();
    TessellationWorker(const TessellationWorker&) = delete;
    TessellationWorker& operator=(const TessellationWorker&) = delete;

    /// Queues `job`, superseding any job queued or running and any result not yet taken. A job
    /// without items only cancels.
    void submit(TessellationJob job);
    /// The finished result of the latest job, once (nullopt while it runs, or when taken already).
    std::optional<TessellationResult> take();
    /// Blocks until no job is queued or running (its result, if any, waits for take()).
    void wait();

    // ---- test hook: interleaving an edit with a running job, without timing
    /// While on, a job that has built its items waits before it publishes its result.
    void setHold(bool hold);
    /// Blocks until a job waits at the hold (setHold(true) first, or this never returns).
    void waitUntilHeld();

private:
    void run(std::stop_token stop);

    std::mutex mutex_;
    std::condition_variable_any changed_;
    std::optional<TessellationJob> queued_;
    std::optional<TessellationResult> done_;
    long latest_ = 0;        // generation of the latest job submitted
    bool running_ = false;
    bool hold_ = false, held_ = false;
    std::jthread thread_;    // last: started after the members above exist, stopped first
};

} // namespace freeform::editor
