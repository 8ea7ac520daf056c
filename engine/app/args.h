// Command-line parsing for the meadow executable: `meadow <command> [positional...] [options]`.
// Each command declares the options it takes; anything else is an error that names the flag.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace meadow {

struct CommandSpec {
    std::string name;
    std::vector<std::string> positionals; // names of the required positional arguments
    std::set<std::string> valueOptions;   // "--out" etc., each followed by a value
    std::set<std::string> switchOptions;  // "--json" etc., no value
};

struct ParsedArgs {
    std::string command;
    std::vector<std::string> positionals;
    std::map<std::string, std::string> values;
    std::set<std::string> switches;

    bool has(const std::string& option) const { return values.count(option) || switches.count(option); }
    std::optional<std::string> value(const std::string& option) const;

    // Typed accessors: throw meadow::Error naming the option and the bad value.
    uint32_t u32(const std::string& option, uint32_t fallback, uint32_t lo, uint32_t hi) const;
    uint64_t u64(const std::string& option, uint64_t fallback) const;
    float f32(const std::string& option, float fallback, float lo, float hi) const;
    // "WxH", each within [1, 16384].
    std::pair<uint32_t, uint32_t> size(const std::string& option, std::pair<uint32_t, uint32_t> fallback) const;
    // A comma-separated list of exactly `count` numbers.
    std::optional<std::vector<float>> floats(const std::string& option, size_t count) const;
};

// `args` excludes the program name and the command. Throws meadow::Error for unknown options,
// missing values and missing or extra positionals.
ParsedArgs parseArgs(const CommandSpec& spec, const std::vector<std::string>& args);

} // namespace meadow
