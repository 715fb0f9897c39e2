// freeform::cli::run: the command line parsed by CLI11 (one subcommand per command, declared by
// the command itself), the command's action run, its JSON printed on `out`, errors as one line on
// `err`. See docs/cli.md.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>
#include <mutex>

#include "command.h"
#include "freeform/core/error.h"
#include "freeform/core/warning.h"

namespace freeform::cli {

namespace {
/// A result that overflowed (inf, nan) would print as null with exit 0: an Error naming the field.
void requireFinite(const Json& value, const std::string& where)
{
    if (value.is_number_float() && !std::isfinite(value.get<double>()))
        throw Error("the result " + (where.empty() ? std::string("value") : "field " + where) +
                    " is not finite (the computation overflowed double precision)");
    if (value.is_object())
        for (auto it = value.begin(); it != value.end(); ++it) requireFinite(it.value(), where + "/" + it.key());
    if (value.is_array())
        for (std::size_t i = 0; i < value.size(); ++i) requireFinite(value[i], where + "/" + std::to_string(i));
}
} // namespace


namespace {

/// CLI11 reads integers with base detection (010 is 8, 0x10 is 16) and floating point with
/// strtold (nan, inf, hex): these validators keep numbers decimal and finite, as documented.
std::string checkInteger(std::string& text)
{
    long v = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (text.empty() || ec != std::errc() || ptr != text.data() + text.size())
        return "\"" + text + "\" is not an integer";
    text = std::to_string(v); // canonical decimal: no leading zeros for the base detection to see
    return {};
}

std::string checkFinite(std::string& text)
{
    double v = 0;
    const char* first = text.data();
    const char* last = first + text.size();
    if (first != last && *first == '+') ++first;
    const auto [ptr, ec] = std::from_chars(first, last, v);
    if (text.empty() || ec != std::errc() || ptr != last || !std::isfinite(v)) return "\"" + text + "\" is not a finite number";
    return {};
}

const CLI::Validator& integerValidator()
{
    static const CLI::Validator v(checkInteger, "INTEGER", "decimal integer");
    return v;
}

const CLI::Validator& finiteValidator()
{
    static const CLI::Validator v(checkFinite, "NUMBER", "finite number");
    return v;
}

std::string oneLine(std::string text)
{
    std::replace(text.begin(), text.end(), '\n', ' ');
    while (!text.empty() && text.back() == ' ') text.pop_back();
    return text;
}

} // namespace

CLI::Option* addPositionals(CLI::App& app, const std::string& name, std::vector<std::string>& values,
                            const std::string& description)
{
    return app.add_option(name, values, description)->type_name("");
}

void expectPositional(const std::vector<std::string>& positional, std::size_t count, const std::string& what)
{
    if (positional.size() < count) throw UsageError("missing " + what);
    if (positional.size() > count) throw UsageError("unexpected argument \"" + positional[count] + "\"");
}

CLI::Option* addNumber(CLI::App& app, const std::string& name, int& value, const std::string& description)
{
    return app.add_option(name, value, description)->transform(integerValidator());
}

CLI::Option* addNumber(CLI::App& app, const std::string& name, long& value, const std::string& description)
{
    return app.add_option(name, value, description)->transform(integerValidator());
}

CLI::Option* addNumber(CLI::App& app, const std::string& name, double& value, const std::string& description)
{
    return app.add_option(name, value, description)->check(finiteValidator());
}

CLI::Option* addFlag(CLI::App& app, const std::string& name, bool& value, const std::string& description)
{
    return app.add_flag(name, value, description)->multi_option_policy(CLI::MultiOptionPolicy::Throw)->disable_flag_override();
}

double parseNumber(const std::string& text, const std::string& option)
{
    std::string copy = text;
    if (!checkFinite(copy).empty()) throw UsageError("option " + option + ": \"" + text + "\" is not a finite number");
    double v = 0;
    const char* first = text.data();
    if (*first == '+') ++first;
    std::from_chars(first, text.data() + text.size(), v);
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

Json pointJson(const double* p, int dim)
{
    Json a = Json::array();
    for (int k = 0; k < dim; ++k) a.push_back(p[k]);
    return a;
}

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err)
{
    // The library's warnings (freeform/core/warning.h): one "warning:" line each on stderr, as the
    // errors; stdout keeps only the JSON.
    std::mutex errMutex; // warnings may come from worker threads
    const ScopedWarningHandler warnings([&err, &errMutex](const std::string& message) {
        const std::lock_guard lock(errMutex);
        err << "warning: " << message << '\n';
    });
    CLI::App app("freeform - Bézier curves, splines, surfaces and free-form deformation", "freeform");
    app.footer("Results are printed as JSON on stdout. Errors are one line starting \"error:\" on stderr;\n"
               "the exit status is 1 for bad input and 2 for bad usage. Documents: docs/format.md.\n"
               "Every command explains its options: freeform COMMAND --help.");
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::Throw);
    app.require_subcommand(1); // exactly one: a later word that names a command is an argument
    std::map<std::string, std::pair<CLI::App*, Action>> actions;
    for (const Command& c : commands()) {
        CLI::App* sub = app.add_subcommand(c.name, c.summary);
        sub->allow_extras(); // unknown options are reported below, by name
        actions[c.name] = {sub, c.define(*sub)};
    }

    if (args.empty()) {
        err << "error: no command given (see freeform --help)\n";
        return 2;
    }
    if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
        out << app.help();
        return 0;
    }
    if (args[0] == "--version") {
        out << "freeform 0.1.0\n";
        return 0;
    }
    const auto it = actions.find(args[0]);
    if (it == actions.end()) {
        err << "error: unknown command \"" << args[0] << "\" (see freeform --help)\n";
        return 2;
    }
    const std::string usage = " (see freeform " + args[0] + " --help)\n";
    CLI::App& sub = *it->second.first;
    try {
        std::vector<std::string> reversed(args.rbegin(), args.rend()); // CLI11 takes them last first
        app.parse(reversed);
    } catch (const CLI::CallForHelp&) {
        out << sub.help("freeform");
        return 0;
    } catch (const CLI::ParseError& e) {
        err << "error: " << oneLine(e.what()) << usage;
        return 2;
    }
    for (const std::string& extra : sub.remaining()) {
        if (extra.size() > 1 && extra[0] == '-') {
            err << "error: unknown option " << extra.substr(0, extra.find('=')) << usage;
            return 2;
        }
        err << "error: unexpected argument \"" << extra << "\"" << usage;
        return 2;
    }
    try {
        const Json result = it->second.second();
        requireFinite(result, "");
        out << result.dump() << '\n';
        return 0;
    } catch (const UsageError& e) {
        err << "error: " << oneLine(e.what()) << usage;
        return 2;
    } catch (const freeform::Error& e) {
        err << "error: " << oneLine(e.what()) << '\n';
        return 1;
    } catch (const std::bad_alloc&) {
        err << "error: out of memory\n";
        return 1;
    } catch (const std::exception& e) {
        err << "error: " << oneLine(e.what()) << '\n';
        return 1;
    }
}

} // namespace freeform::cli
