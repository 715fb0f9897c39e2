// freeform: the command-line tool. See `freeform --help` and docs/cli.md.

#include <cmath>
#include <charconv>
#include <iostream>

#include "command.h"
#include "freeform/core/error.h"

namespace freeform::cli {

Args::Args(const std::vector<std::string>& argv, const std::set<std::string>& valueOptions,
           const std::set<std::string>& flags)
{
    for (std::size_t i = 0; i < argv.size(); ++i) {
        const std::string& a = argv[i];
        if (a.size() > 2 && a.rfind("--", 0) == 0) {
            std::string name = a.substr(2), value;
            const auto eq = name.find('=');
            const bool inlineValue = eq != std::string::npos;
            if (inlineValue) {
                value = name.substr(eq + 1);
                name = name.substr(0, eq);
            }
            if (valueOptions.count(name)) {
                if (!inlineValue) {
                    if (i + 1 >= argv.size()) throw UsageError("option --" + name + " needs a value");
                    value = argv[++i];
                }
            } else if (flags.count(name)) {
                if (inlineValue) throw UsageError("option --" + name + " takes no value");
            } else {
                throw UsageError("unknown option --" + name);
            }
            if (options_.count(name)) throw UsageError("option --" + name + " is given twice");
            options_[name] = value;
        } else if (a == "-o") {
            if (!valueOptions.count("output")) throw UsageError("unknown option -o");
            if (i + 1 >= argv.size()) throw UsageError("option -o needs a value");
            if (options_.count("output")) throw UsageError("option -o is given twice");
            options_["output"] = argv[++i];
        } else if (a.size() > 1 && a[0] == '-' && !(std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')) {
            throw UsageError("unknown option " + a);
        } else {
            positional_.push_back(a);
        }
    }
}

std::optional<std::string> Args::get(const std::string& name) const
{
    const auto it = options_.find(name);
    if (it == options_.end()) return std::nullopt;
    return it->second;
}

std::string Args::required(const std::string& name) const
{
    const auto v = get(name);
    if (!v) throw UsageError("option --" + name + " is required");
    return *v;
}

void Args::expectPositional(std::size_t count, const std::string& what) const
{
    if (positional_.size() < count) throw UsageError("missing " + what);
    if (positional_.size() > count) throw UsageError("unexpected argument \"" + positional_[count] + "\"");
}

double parseNumber(const std::string& text, const std::string& option)
{
    double v = 0;
    const char* first = text.data();
    const char* last = first + text.size();
    if (first != last && *first == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || ptr != last || text.empty() || !std::isfinite(v))
        throw UsageError("option " + option + ": \"" + text + "\" is not a finite number");
    return v;
}

int parseInteger(const std::string& text, const std::string& option)
{
    int v = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size() || text.empty())
        throw UsageError("option " + option + ": \"" + text + "\" is not an integer");
    return v;
}

std::vector<double> parseNumberList(const std::string& text, const std::string& option, std::size_t count)
{
    std::vector<double> out;
    std::size_t start = 0;
    while (true) {
        const auto comma = text.find(',', start);
        out.push_back(parseNumber(text.substr(start, comma - start), option));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (count != 0 && out.size() != count)
        throw UsageError("option " + option + ": expected " + std::to_string(count) + " comma-separated numbers, found " +
                         std::to_string(out.size()));
    return out;
}

/// A result that overflowed (inf, nan) would print as null with exit 0: an Error naming the field.
static void requireFinite(const Json& value, const std::string& where)
{
    if (value.is_number_float() && !std::isfinite(value.get<double>()))
        throw Error("the result " + (where.empty() ? std::string("value") : "field " + where) +
                    " is not finite (the computation overflowed double precision)");
    if (value.is_object())
        for (auto it = value.begin(); it != value.end(); ++it) requireFinite(it.value(), where + "/" + it.key());
    if (value.is_array())
        for (std::size_t i = 0; i < value.size(); ++i) requireFinite(value[i], where + "/" + std::to_string(i));
}

void printJson(const Json& value)
{
    requireFinite(value, "");
    std::cout << value.dump() << '\n';
}

Json pointJson(const double* p, int dim)
{
    Json a = Json::array();
    for (int k = 0; k < dim; ++k) a.push_back(p[k]);
    return a;
}

const DocumentObject& findLattice(const Document& doc, const std::optional<std::string>& name)
{
    if (name) {
        const DocumentObject& o = doc.object(*name);
        if (!std::holds_alternative<LatticeData>(o.data))
            throw Error(doc.source + ": object \"" + *name + "\" is a " + objectType(o.data) + ", not a lattice");
        return o;
    }
    const DocumentObject* found = nullptr;
    for (const DocumentObject& o : doc.objects) {
        if (!std::holds_alternative<LatticeData>(o.data)) continue;
        if (found) throw Error(doc.source + ": has several lattices; choose one with --object");
        found = &o;
    }
    if (!found) throw Error(doc.source + ": has no lattice object");
    return *found;
}

std::map<std::string, Command>& commands()
{
    static std::map<std::string, Command> registry;
    return registry;
}

std::map<std::string, Evaluator>& evaluators()
{
    static std::map<std::string, Evaluator> registry;
    return registry;
}

namespace {

std::string mainHelp()
{
    std::string text =
        "freeform - Bézier curves, splines, surfaces and free-form deformation\n"
        "\n"
        "usage: freeform COMMAND [ARGS...]\n"
        "       freeform COMMAND --help\n"
        "\n"
        "commands:\n";
    for (const auto& [name, c] : commands()) {
        text += "  " + name + std::string(name.size() < 12 ? 12 - name.size() : 1, ' ') + c.summary + "\n";
    }
    text +=
        "\n"
        "Results are printed as JSON on stdout. Errors are one line starting \"error:\" on stderr;\n"
        "the exit status is 1 for bad input and 2 for bad usage. Documents: docs/format.md.\n";
    return text;
}

} // namespace
} // namespace freeform::cli

int main(int argc, char** argv)
{
    using namespace freeform::cli;
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty()) {
        std::cerr << "error: no command given (see freeform --help)\n";
        return 2;
    }
    if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        std::cout << mainHelp();
        return 0;
    }
    if (args[0] == "--version") {
        std::cout << "freeform 0.1.0\n";
        return 0;
    }
    const auto it = commands().find(args[0]);
    if (it == commands().end()) {
        std::cerr << "error: unknown command \"" << args[0] << "\" (see freeform --help)\n";
        return 2;
    }
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    for (const auto& a : rest) {
        if (a == "--help" || a == "-h") {
            std::cout << it->second.help;
            return 0;
        }
    }
    try {
        return it->second.run(rest);
    } catch (const UsageError& e) {
        std::cerr << "error: " << e.what() << " (see freeform " << args[0] << " --help)\n";
        return 2;
    } catch (const freeform::Error& e) {
        std::cerr << "error: " << e.what() << '\n';
        return 1;
    } catch (const std::bad_alloc&) {
        std::cerr << "error: out of memory\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << '\n';
        return 1;
    }
}
