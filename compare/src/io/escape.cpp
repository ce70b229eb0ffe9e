#include "io/escape.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace linequad::escape {

namespace {

bool ascii_punctuation(unsigned char c) {
    return (c >= 0x21 && c <= 0x2F) || (c >= 0x3A && c <= 0x40) || (c >= 0x5B && c <= 0x60) ||
           (c >= 0x7B && c <= 0x7E);
}

bool control(unsigned char c) {
    return c < 0x20 || c == 0x7F;
}

std::size_t longest_backtick_run(std::string_view s) {
    std::size_t best = 0, run = 0;
    for (char c : s) {
        run = c == '`' ? run + 1 : 0;
        best = std::max(best, run);
    }
    return best;
}

std::string one_line(std::string_view s) {
    std::string out(s);
    for (char& c : out)
        if (control(static_cast<unsigned char>(c))) c = ' ';
    return out;
}

} // namespace

std::string shell_word(std::string_view s) {
    std::string out = "'";
    for (char c : s) {
        if (c == '\'')
            out += "'\\''";
        else
            out += c;
    }
    return out + "'";
}

std::string markdown_text(std::string_view s) {
    std::string out;
    out.reserve(s.size() + s.size() / 4);
    for (char c : s) {
        auto u = static_cast<unsigned char>(c);
        if (control(u))
            out += ' ';
        else if (ascii_punctuation(u))
            out += '\\', out += c;
        else
            out += c;
    }
    return out;
}

std::string markdown_code(std::string_view s) {
    std::string text = one_line(s);
    std::string fence(longest_backtick_run(text) + 1, '`');
    // A span that starts or ends with a backtick (or a space) needs a space inside its fence,
    // which CommonMark strips once from each end.
    bool pad = !text.empty() && (text.front() == '`' || text.back() == '`' || text.front() == ' ' ||
                                 text.back() == ' ');
    if (text.empty()) return "` `";
    return fence + (pad ? " " : "") + text + (pad ? " " : "") + fence;
}

std::string markdown_block(const std::vector<std::string>& lines, std::string_view indent) {
    std::size_t run = 0;
    for (const std::string& l : lines)
        run = std::max(run, longest_backtick_run(l));
    std::string fence(std::max<std::size_t>(3, run + 1), '`');
    std::string out = std::string(indent) + fence + "\n";
    for (const std::string& l : lines)
        out += std::string(indent) + one_line(l) + "\n";
    return out + std::string(indent) + fence + "\n";
}

std::string file_name(std::string_view s) {
    std::string out;
    for (char c : s) {
        auto u = static_cast<unsigned char>(c);
        if ((u >= '0' && u <= '9') || (u >= 'a' && u <= 'z') || (u >= 'A' && u <= 'Z') ||
            u == '_') {
            out += c;
        } else {
            char hex[4];
            std::snprintf(hex, sizeof hex, "-%02X", unsigned(u));
            out += hex;
        }
    }
    if (out.size() <= 80) return out;
    std::uint64_t h = 1469598103934665603ull; // FNV-1a of the whole name
    for (char c : s)
        h = (h ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    char tail[24];
    std::snprintf(tail, sizeof tail, "-%016llx", static_cast<unsigned long long>(h));
    return out.substr(0, 60) + tail;
}

} // namespace linequad::escape
