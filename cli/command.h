#pragma once
// The `freeform` command-line tool: subcommands register themselves here (one file each), so a
// new subcommand is a new file and nothing else changes.
//
// Contract (docs/cli.md): results are JSON on stdout; errors are one line "error: ..." on stderr
// with exit status 1 for bad input and 2 for bad usage, and then nothing is written to stdout and
// no output file is left behind.

#include <nlohmann/json.hpp>

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "freeform/io/document.h"

namespace freeform::cli {

using Json = nlohmann::ordered_json;

/// Bad usage (unknown option, missing argument, malformed number): exit status 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The arguments of one subcommand: positionals, "--name value" options and "--flag" switches.
class Args {
public:
    Args(const std::vector<std::string>& argv, const std::set<std::string>& valueOptions,
         const std::set<std::string>& flags);

    const std::vector<std::string>& positional() const { return positional_; }
    std::optional<std::string> get(const std::string& name) const;
    std::string required(const std::string& name) const;
    bool has(const std::string& name) const { return options_.count(name) != 0; }
    /// Exactly `count` positional arguments, else UsageError naming `what`.
    void expectPositional(std::size_t count, const std::string& what) const;

private:
    std::vector<std::string> positional_;
    std::map<std::string, std::string> options_;
};

/// A number from the command line; UsageError naming the option when it is not a finite number.
double parseNumber(const std::string& text, const std::string& option);
int parseInteger(const std::string& text, const std::string& option);
/// "a,b,c" into exactly `count` numbers (count 0: any positive count).
std::vector<double> parseNumberList(const std::string& text, const std::string& option, std::size_t count);

/// Prints a JSON value on stdout (one line, numbers in shortest round-trip form).
void printJson(const Json& value);

/// A point as a JSON array.
Json pointJson(const double* p, int dim);

/// The lattice object `name` of the document, or its only lattice when no name is given; Error
/// naming the document when it is not a lattice, when there are several, or none.
const DocumentObject& findLattice(const Document& doc, const std::optional<std::string>& name);

struct Command {
    std::string name;
    std::string summary; // one line for `freeform --help`
    std::string help;    // the full text for `freeform NAME --help`
    int (*run)(const std::vector<std::string>& args);
};

/// The registered subcommands, by name.
std::map<std::string, Command>& commands();

struct RegisterCommand {
    explicit RegisterCommand(Command c) { commands()[c.name] = std::move(c); }
};

/// `freeform eval` dispatches on the object type. Each geometry registers one evaluator:
/// given the object, the text of --at and the derivative order K, it returns the JSON result.
using Evaluator = Json (*)(const Document& doc, const DocumentObject& object, const std::string& at, int order);
std::map<std::string, Evaluator>& evaluators();

struct RegisterEvaluator {
    RegisterEvaluator(const std::string& type, Evaluator e) { evaluators()[type] = e; }
};

} // namespace freeform::cli
