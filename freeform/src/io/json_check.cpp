// checkJsonText: nlohmann's SAX parser (iterative) with a handler that counts depth and remembers
// the keys of each open object.

#include "freeform/io/json_check.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <set>
#include <vector>

#include "freeform/core/error.h"

namespace freeform {

namespace {

using PlainJson = nlohmann::json;

class CheckingSax {
public:
    explicit CheckingSax(int maxDepth) : maxDepth_(maxDepth) {}

    std::string problem;   // set when the handler stopped the parse
    bool syntax = false;   // the text is not valid JSON

    bool null() { return value(); }
    bool boolean(bool) { return value(); }
    bool number_integer(PlainJson::number_integer_t) { return value(); }
    bool number_unsigned(PlainJson::number_unsigned_t) { return value(); }
    bool number_float(PlainJson::number_float_t, const std::string&) { return value(); }
    bool string(std::string&) { return value(); }
    bool binary(PlainJson::binary_t&) { return value(); }

    bool start_object(std::size_t) { return open(false); }
    bool end_object() { return close(); }
    bool start_array(std::size_t) { return open(true); }
    bool end_array() { return close(); }
    bool key(std::string& k)
    {
        Frame& f = frames_.back();
        if (!f.keys.insert(k).second) {
            problem = "the key \"" + k + "\" appears twice in one object" + where(frames_.size() - 1);
            return false;
        }
        f.key = k;
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&)
    {
        syntax = true; // left to the parser that follows (its message names the position)
        return false;
    }

private:
    // One open array or object: the index of its current element, or its keys so far and the
    // current one (for the location in the message).
    struct Frame {
        bool array = false;
        std::size_t index = 0;
        std::set<std::string> keys;
        std::string key;
    };

    bool value()
    {
        if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
        return true;
    }
    bool open(bool array)
    {
        value();
        if (static_cast<int>(frames_.size()) + 1 > maxDepth_) {
            problem = "values are nested deeper than " + std::to_string(maxDepth_) + " levels" + where(frames_.size());
            return false;
        }
        frames_.push_back(Frame{array, 0, {}, {}});
        return true;
    }
    bool close()
    {
        frames_.pop_back();
        return true;
    }

    // " (at objects[0].editor.a...)": the path to the value being read through the outer `levels`
    // open values, its first components only (at the depth limit it is hundreds long); empty at
    // the top level.
    std::string where(std::size_t levels) const
    {
        constexpr std::size_t kShown = 8;
        std::string path;
        std::size_t shown = 0;
        for (std::size_t i = 0; i < levels; ++i) {
            const Frame& f = frames_[i];
            if (shown == kShown) {
                path += "...";
                break;
            }
            if (f.array) {
                if (f.index == 0) break; // an array with no element yet: the array itself
                path += '[';
                path += std::to_string(f.index - 1);
                path += ']';
            } else {
                if (f.key.empty() && f.keys.empty()) break; // an object before its first key
                if (!path.empty()) path += ".";
                path += f.key;
            }
            ++shown;
        }
        if (path.empty()) return path;
        std::string at(" (at ");
        at += path;
        at += ')';
        return at;
    }

    int maxDepth_;
    std::vector<Frame> frames_;
};

} // namespace

void checkJsonText(std::string_view text, const std::string& source, int maxDepth)
{
    CheckingSax sax(maxDepth);
    bool ok = false;
    try {
        ok = PlainJson::sax_parse(text.begin(), text.end(), &sax);
    } catch (const PlainJson::exception&) {
        return; // a syntax error: the parser that follows reports it with its position
    }
    if (ok || sax.syntax) return;
    throw Error(source + ": " + sax.problem);
}

} // namespace freeform
