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

using Json = nlohmann::json;

class CheckingSax {
public:
    explicit CheckingSax(int maxDepth) : maxDepth_(maxDepth) {}

    std::string problem;   // set when the handler stopped the parse
    bool syntax = false;   // the text is not valid JSON

    bool null() { return true; }
    bool boolean(bool) { return true; }
    bool number_integer(Json::number_integer_t) { return true; }
    bool number_unsigned(Json::number_unsigned_t) { return true; }
    bool number_float(Json::number_float_t, const std::string&) { return true; }
    bool string(std::string&) { return true; }
    bool binary(Json::binary_t&) { return true; }

    bool start_object(std::size_t) { return open(true); }
    bool end_object()
    {
        keys_.pop_back();
        --depth_;
        return true;
    }
    bool start_array(std::size_t) { return open(false); }
    bool end_array()
    {
        keys_.pop_back();
        --depth_;
        return true;
    }
    bool key(std::string& k)
    {
        if (!keys_.back().insert(k).second) {
            problem = "the key \"" + k + "\" appears twice in one object";
            return false;
        }
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&)
    {
        syntax = true; // left to the parser that follows (its message names the position)
        return false;
    }

private:
    bool open(bool object)
    {
        if (++depth_ > maxDepth_) {
            problem = "values are nested deeper than " + std::to_string(maxDepth_) + " levels";
            return false;
        }
        keys_.emplace_back();
        (void)object;
        return true;
    }

    int maxDepth_;
    int depth_ = 0;
    std::vector<std::set<std::string>> keys_;
};

} // namespace

void checkJsonText(std::string_view text, const std::string& source, int maxDepth)
{
    CheckingSax sax(maxDepth);
    bool ok = false;
    try {
        ok = Json::sax_parse(text.begin(), text.end(), &sax);
    } catch (const Json::exception&) {
        return; // a syntax error: the parser that follows reports it with its position
    }
    if (ok || sax.syntax) return;
    throw Error(source + ": " + sax.problem);
}

} // namespace freeform
