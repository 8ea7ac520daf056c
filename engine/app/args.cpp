#include "app/args.h"
#include "app/commands.h"

#include "core/error.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace meadow {
namespace {

[[noreturn]] void bad(const std::string& command, const std::string& option, const std::string& value,
                      const std::string& expected) {
    throw Error("meadow " + command + ": " + option + " '" + value + "' is not " + expected);
}

bool parseU64(const std::string& s, uint64_t& out) {
    if (s.empty() || s[0] == '-' || s[0] == '+')
        return false;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
    return ec == std::errc() && end == s.data() + s.size();
}

bool parseFloat(const std::string& s, float& out) {
    if (s.empty())
        return false;
    char* end = nullptr;
    out = std::strtof(s.c_str(), &end);
    return end == s.c_str() + s.size() && std::isfinite(out);
}

std::string shortNumber(float f) {
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%g", static_cast<double>(f));
    return buf;
}

} // namespace

std::optional<std::string> ParsedArgs::value(const std::string& option) const {
    auto it = values.find(option);
    if (it == values.end())
        return std::nullopt;
    return it->second;
}

uint32_t ParsedArgs::u32(const std::string& option, uint32_t fallback, uint32_t lo, uint32_t hi) const {
    auto v = value(option);
    if (!v)
        return fallback;
    uint64_t n;
    if (!parseU64(*v, n) || n < lo || n > hi)
        bad(command, option, *v, "an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
    return static_cast<uint32_t>(n);
}

uint64_t ParsedArgs::u64(const std::string& option, uint64_t fallback) const {
    auto v = value(option);
    if (!v)
        return fallback;
    uint64_t n;
    if (!parseU64(*v, n))
        bad(command, option, *v, "a non-negative integer");
    return n;
}

float ParsedArgs::f32(const std::string& option, float fallback, float lo, float hi) const {
    auto v = value(option);
    if (!v)
        return fallback;
    float f;
    if (!parseFloat(*v, f) || f < lo || f > hi)
        bad(command, option, *v, "a number from " + shortNumber(lo) + " to " + shortNumber(hi));
    return f;
}

std::pair<uint32_t, uint32_t> ParsedArgs::size(const std::string& option,
                                               std::pair<uint32_t, uint32_t> fallback) const {
    auto v = value(option);
    if (!v)
        return fallback;
    size_t x = v->find('x');
    uint64_t w, h;
    if (x == std::string::npos || !parseU64(v->substr(0, x), w) || !parseU64(v->substr(x + 1), h) || w < 1 || h < 1 ||
        w > 16384 || h > 16384)
        bad(command, option, *v, "a size WxH with each side from 1 to 16384 (e.g. 1280x720)");
    return {static_cast<uint32_t>(w), static_cast<uint32_t>(h)};
}

std::optional<std::vector<float>> ParsedArgs::floats(const std::string& option, size_t count) const {
    auto v = value(option);
    if (!v)
        return std::nullopt;
    std::vector<float> out;
    size_t start = 0;
    while (start <= v->size()) {
        size_t comma = v->find(',', start);
        std::string part = v->substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        float f;
        if (!parseFloat(part, f))
            bad(command, option, *v, std::to_string(count) + " comma-separated numbers");
        out.push_back(f);
        if (comma == std::string::npos)
            break;
        start = comma + 1;
    }
    if (out.size() != count)
        bad(command, option, *v, std::to_string(count) + " comma-separated numbers");
    return out;
}

ParsedArgs parseArgs(const CommandSpec& spec, const std::vector<std::string>& args) {
    ParsedArgs parsed;
    parsed.command = spec.name;
    const std::string where = "meadow " + spec.name + ": ";
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a.size() > 2 && a.rfind("--", 0) == 0) {
            std::string name = a, inlineValue;
            bool hasInline = false;
            if (size_t eq = a.find('='); eq != std::string::npos) {
                name = a.substr(0, eq);
                inlineValue = a.substr(eq + 1);
                hasInline = true;
            }
            if (spec.valueOptions.count(name)) {
                if (!hasInline) {
                    if (i + 1 >= args.size())
                        throw Error(where + name + " needs a value");
                    inlineValue = args[++i];
                }
                if (parsed.values.count(name))
                    throw Error(where + name + " is given twice");
                parsed.values[name] = inlineValue;
            } else if (spec.switchOptions.count(name)) {
                if (hasInline)
                    throw Error(where + name + " takes no value");
                parsed.switches.insert(name);
            } else {
                throw Error(where + "unknown option " + name + " (see meadow " + spec.name + " --help)");
            }
        } else if (a.size() > 1 && a[0] == '-' && !(a[1] >= '0' && a[1] <= '9')) {
            throw Error(where + "unknown option " + a + " (see meadow " + spec.name + " --help)");
        } else {
            parsed.positionals.push_back(a);
        }
    }
    if (parsed.positionals.size() < spec.positionals.size())
        throw Error(where + "missing " + spec.positionals[parsed.positionals.size()] + " (see meadow " + spec.name +
                    " --help)");
    if (parsed.positionals.size() > spec.positionals.size())
        throw Error(where + "unexpected argument '" + parsed.positionals[spec.positionals.size()] + "'");
    return parsed;
}

bool printHelpIfAsked(const Args& args, const char* text) {
    for (const std::string& a : args)
        if (a == "--help" || a == "-h") {
            std::fputs(text, stdout);
            return true;
        }
    return false;
}

} // namespace meadow
