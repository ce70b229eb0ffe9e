#include "io/escape.hpp"

#include <algorithm>
#include <cctype>
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
    // A control character (a newline in a path) cannot stand in single quotes where the command
    // is shown (a markdown code span makes a line break a space, another file): the word is then
    // ANSI-C quoted, $'...', every such byte as \xHH, which bash and zsh read as the byte.
    bool plain = std::none_of(s.begin(), s.end(),
                              [](char c) { return control(static_cast<unsigned char>(c)); });
    if (!plain) {
        std::string out = "$'";
        for (char c : s) {
            auto u = static_cast<unsigned char>(c);
            if (control(u) || c == '\'' || c == '\\') {
                char hex[5];
                std::snprintf(hex, sizeof hex, "\\x%02x", u);
                out += hex;
            } else {
                out += c;
            }
        }
        return out + "'";
    }
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

std::string anchor(std::string_view s) {
    std::string out;
    bool gap = false;
    for (char ch : s) {
        unsigned char c = static_cast<unsigned char>(ch);
        if (std::isalnum(c) && c < 128) {
            if (gap && !out.empty()) out += '-';
            out += char(std::tolower(c));
            gap = false;
        } else {
            gap = true;
        }
    }
    return out;
}

namespace {

// One line of markdown inline text as it reads: "\|" is "|", "**x**" is "x", "`x`" is "x".
std::string inline_text(std::string_view line) {
    std::string out;
    for (std::size_t i = 0; i < line.size(); ++i) {
        char c = line[i];
        if (c == '\\' && i + 1 < line.size() &&
            std::ispunct(static_cast<unsigned char>(line[i + 1]))) {
            out += line[++i];
        } else if (c == '*' && i + 1 < line.size() && line[i + 1] == '*') {
            ++i;
        } else if (c != '`') {
            out += c;
        }
    }
    return out;
}

// A table row's cells: split at the | that are not escaped, the outer ones dropped.
std::vector<std::string> cells_of(std::string_view line) {
    std::vector<std::string> cells;
    std::string cell;
    for (std::size_t i = 1; i < line.size(); ++i) {
        if (line[i] == '\\' && i + 1 < line.size()) {
            cell += line[i], cell += line[++i];
        } else if (line[i] == '|') {
            std::size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
            cells.push_back(a == std::string::npos ? "" : inline_text(cell.substr(a, b - a + 1)));
            cell.clear();
        } else {
            cell += line[i];
        }
    }
    return cells;
}

bool is_rule(const std::vector<std::string>& cells) {
    for (const std::string& c : cells)
        if (c.empty() || c.find_first_not_of("-:") != std::string::npos) return false;
    return !cells.empty();
}

// Characters as a terminal shows them: UTF-8 continuation bytes take no column.
std::size_t columns(const std::string& s) {
    std::size_t n = 0;
    for (unsigned char c : s)
        n += (c & 0xC0) != 0x80;
    return n;
}

} // namespace

std::string markdown_as_text(std::string_view md) {
    std::vector<std::string> lines;
    for (std::size_t at = 0; at <= md.size();) {
        std::size_t nl = md.find('\n', at);
        if (nl == std::string_view::npos) nl = md.size();
        lines.emplace_back(md.substr(at, nl - at));
        at = nl + 1;
    }
    std::string out;
    for (std::size_t i = 0; i < lines.size();) {
        if (lines[i].empty() || lines[i][0] != '|') {
            std::string line = lines[i++];
            std::size_t hashes = line.find_first_not_of('#');
            if (hashes != std::string::npos && hashes > 0 && line[hashes] == ' ')
                line = line.substr(hashes + 1); // a heading: its text
            out += inline_text(line) + (i < lines.size() ? "\n" : "");
            continue;
        }
        std::vector<std::vector<std::string>> table;
        std::vector<std::size_t> width;
        for (; i < lines.size() && !lines[i].empty() && lines[i][0] == '|'; ++i) {
            table.push_back(cells_of(lines[i]));
            for (std::size_t c = 0; c < table.back().size(); ++c) {
                if (width.size() <= c) width.push_back(0);
                if (!is_rule(table.back())) width[c] = std::max(width[c], columns(table.back()[c]));
            }
        }
        for (const std::vector<std::string>& row : table) {
            std::string line;
            for (std::size_t c = 0; c < row.size(); ++c) {
                std::string cell = is_rule(row) ? std::string(width[c], '-') : row[c];
                line += (c ? "  " : "") + cell;
                if (c + 1 < row.size()) line += std::string(width[c] - columns(cell), ' ');
            }
            out += line + "\n";
        }
    }
    return out;
}

} // namespace linequad::escape
