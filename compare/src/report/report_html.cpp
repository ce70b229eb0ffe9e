// report.md to report.html through cmark-gfm (Debian libcmark-gfm-dev, GitHub's own renderer, with
// its table extension), the figures inlined as data: URIs.
#include "report/report_html.hpp"

#include "io/escape.hpp"
#include "io/jsonl.hpp"

#include <cmark-gfm-core-extensions.h>
#include <cmark-gfm.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace linequad::audit {

namespace {

std::string base64(const std::string& bytes) {
    static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        unsigned v = unsigned(std::uint8_t(bytes[i])) << 16 |
                     unsigned(std::uint8_t(bytes[i + 1])) << 8 | std::uint8_t(bytes[i + 2]);
        for (int s = 18; s >= 0; s -= 6)
            out += digits[(v >> s) & 63];
    }
    if (std::size_t left = bytes.size() - i) {
        unsigned v = unsigned(std::uint8_t(bytes[i])) << 16 |
                     (left == 2 ? unsigned(std::uint8_t(bytes[i + 1])) << 8 : 0u);
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += left == 2 ? digits[(v >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

// A figure the report names by its file name beside it: letters, digits and _ . - only (no path,
// no scheme, no hidden file), ending .svg.
const char* media_type(const std::string& name) {
    auto ends = [&](const char* e) {
        std::size_t n = std::strlen(e);
        return name.size() > n && name.compare(name.size() - n, n, e) == 0;
    };
    if (name.empty() || name[0] == '.' || name.size() > 200) return nullptr;
    for (char c : name)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-'))
            return nullptr;
    return ends(".svg") ? "image/svg+xml" : nullptr;
}

// A link to an anchor of the page itself: '#' and an anchor's characters (escape::anchor).
bool within_page(const std::string& url) {
    if (url.size() < 2 || url[0] != '#') return false;
    for (std::size_t i = 1; i < url.size(); ++i)
        if (!(std::islower(static_cast<unsigned char>(url[i])) ||
              std::isdigit(static_cast<unsigned char>(url[i])) || url[i] == '-'))
            return false;
    return true;
}

// The text a person reads in a rendered heading: tags dropped, cmark's four entities decoded.
std::string heading_text(const std::string& html) {
    std::string text;
    bool in_tag = false;
    for (char c : html) {
        if (c == '<') in_tag = true;
        if (!in_tag) text += c;
        if (c == '>') in_tag = false;
    }
    std::string out;
    for (std::size_t i = 0; i < text.size(); ++i) {
        static const std::pair<const char*, char> entities[] = {
            {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&quot;", '"'}};
        bool decoded = false;
        for (const auto& [name, c] : entities)
            if (text.compare(i, std::strlen(name), name) == 0) {
                out += c, i += std::strlen(name) - 1, decoded = true;
                break;
            }
        if (!decoded) out += text[i];
    }
    return out;
}

// The sections of the page, each from its h2 to the next, given the heading's anchor as id (what
// the contents link to): the verdict is <section id="verdict">. The full tables a person rarely
// needs first are <details>, closed. cmark's output holds no raw HTML of the report's (it was
// made text), so every "<h2>" in it is a heading.
std::string sectioned(const std::string& body) {
    static const char* const collapsed[] = {"by-family-and-shape", "float-beside-double",
                                            "the-correct-solvers-rungs", "oracle-rounding"};
    std::string out;
    std::size_t at = body.find("<h2>");
    out += body.substr(0, at);
    while (at != std::string::npos) {
        std::size_t close = body.find("</h2>", at);
        if (close == std::string::npos) {
            out += body.substr(at); // never from cmark; kept whole all the same
            break;
        }
        std::size_t next = body.find("<h2>", close);
        std::string heading = body.substr(at, close + 5 - at);
        std::string id = escape::anchor(heading_text(heading.substr(4, heading.size() - 9)));
        std::string rest = body.substr(close + 5, next == std::string::npos ? std::string::npos
                                                                            : next - close - 5);
        bool folded =
            std::find(std::begin(collapsed), std::end(collapsed), id) != std::end(collapsed);
        if (folded)
            out += "<details id=\"" + id + "\"><summary>" + heading + "</summary>" + rest +
                   "</details>\n";
        else
            out += "<section id=\"" + id + "\">" + heading + rest + "</section>\n";
        at = next;
    }
    return out;
}

struct Document {
    cmark_parser* parser = nullptr;
    cmark_node* root = nullptr;
    ~Document() {
        if (root) cmark_node_free(root);
        if (parser) cmark_parser_free(parser);
    }
};

// The page's own style and behaviour. The Content-Security-Policy lets the page load nothing
// from anywhere: its images are data: URIs, its style and script are in the file.
constexpr const char* head = R"(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta http-equiv="Content-Security-Policy" content="default-src 'none'; img-src data:; style-src 'unsafe-inline'; script-src 'unsafe-inline'">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>linequad accuracy audit</title>
<style>
body { font: 15px/1.45 system-ui, sans-serif; margin: 2em auto; max-width: 80em; padding: 0 1em; color: #1b1b1b; }
h1, h2, h3 { line-height: 1.2; }
h3 { font-size: 1em; font-family: ui-monospace, monospace; }
.table-wrap { overflow-x: auto; margin: 1em 0; }
table { border-collapse: collapse; font-size: 13px; }
th, td { border: 1px solid #d0d0d0; padding: 0.25em 0.5em; }
th { background: #f2f2f2; position: sticky; top: 0; cursor: pointer; user-select: none; white-space: nowrap; }
th[aria-sort="ascending"]::after { content: " \25B2"; }
th[aria-sort="descending"]::after { content: " \25BC"; }
tbody tr:nth-child(even) { background: #fafafa; }
code, pre { font-family: ui-monospace, monospace; font-size: 12px; }
pre { background: #f6f6f6; padding: 0.5em; overflow-x: auto; }
img { max-width: 100%; height: auto; }
.replay { display: flex; gap: 0.5em; align-items: flex-start; }
.replay code { background: #f6f6f6; padding: 0.2em 0.4em; word-break: break-all; flex: 1; }
.replay button { flex: none; }
.figure-missing { color: #8a4b00; font-style: italic; }
#verdict table { font-size: 12.5px; }
#verdict th, #verdict td { padding: 0.12em 0.45em; }
#verdict .table-wrap { margin: 0.5em 0; }
#verdict h2 { margin: 0.4em 0 0.3em; }
#verdict h3 { margin: 0.8em 0 0.2em; font-family: inherit; }
#verdict p { margin: 0.4em 0; }
details > summary { cursor: pointer; }
details > summary h2 { display: inline; }
</style>
</head>
<body>
)";

constexpr const char* tail = R"(<script>
"use strict";
// A cell's sort key: its first number ("12 of 300, p99 4.5" sorts by 12; "inf" is the largest;
// "-" has none and sorts last), else its text.
function sortKey(text) {
  const t = text.trim();
  if (t === "-" || t === "") return { n: null, s: "" };
  if (/^inf\b/.test(t)) return { n: Infinity, s: t };
  const m = t.match(/^[+-]?(\d+\.?\d*|\.\d+)(e[+-]?\d+)?/i);
  return m ? { n: parseFloat(m[0]), s: t } : { n: null, s: t };
}
function compareKeys(a, b) {
  if (a.n !== null && b.n !== null) return a.n - b.n;
  if (a.n !== null) return -1;
  if (b.n !== null) return 1;
  return a.s.localeCompare(b.s);
}
function makeSortable(table) {
  const headers = table.querySelectorAll("thead th");
  const body = table.tBodies[0];
  if (!body) return;
  headers.forEach((th, column) => {
    th.setAttribute("title", "sort by this column");
    th.addEventListener("click", () => {
      const descending = th.getAttribute("aria-sort") === "ascending";
      headers.forEach(h => h.removeAttribute("aria-sort"));
      th.setAttribute("aria-sort", descending ? "descending" : "ascending");
      const rows = Array.from(body.rows).map((row, i) => ({ row, i, key: sortKey(row.cells[column] ? row.cells[column].textContent : "") }));
      rows.sort((a, b) => (descending ? -1 : 1) * compareKeys(a.key, b.key) || a.i - b.i);
      rows.forEach(r => body.appendChild(r.row));
    });
  });
}
function copyText(text) {
  if (navigator.clipboard && window.isSecureContext)
    return navigator.clipboard.writeText(text);
  // file:// pages may have no clipboard API: copy through a selection.
  const area = document.createElement("textarea");
  area.value = text;
  document.body.appendChild(area);
  area.select();
  const ok = document.execCommand("copy");
  area.remove();
  return ok ? Promise.resolve() : Promise.reject(new Error("copy refused"));
}
function addCopyButton(code) {
  const wrap = document.createElement("div");
  wrap.className = "replay";
  code.parentNode.insertBefore(wrap, code);
  wrap.appendChild(code);
  const button = document.createElement("button");
  button.type = "button";
  button.textContent = "copy";
  button.addEventListener("click", () => {
    copyText(code.textContent).then(() => { button.textContent = "copied"; },
                                    () => { button.textContent = "select and copy"; });
  });
  wrap.appendChild(button);
}
document.querySelectorAll("table").forEach(table => {
  const wrap = document.createElement("div");
  wrap.className = "table-wrap";
  table.parentNode.insertBefore(wrap, table);
  wrap.appendChild(table);
  makeSortable(table);
});
// The verdict's family table as a heat map: green where a solver misclassifies nothing, through
// yellow, to red from 10 % (a log scale from 0.01 %).
document.querySelectorAll("#verdict h3").forEach(h => {
  if (!h.textContent.startsWith("Misclassified")) return;
  const wrap = h.nextElementSibling;
  const table = wrap && wrap.querySelector("table");
  if (!table) return;
  table.querySelectorAll("tbody td").forEach(td => {
    const t = td.textContent.trim();
    let p = null;
    if (t === "0 %") p = 0;
    else if (t.startsWith("< 0.01")) p = 0.005;
    else if (t.startsWith("> 99.99")) p = 99.995;
    else { const m = t.match(/^(\d+(\.\d+)?) %$/); if (m) p = parseFloat(m[1]); }
    if (p === null) return;
    // Any share above 0 leaves the pale green of 0 for yellow-green and beyond: a tiny share must
    // not read greener than none.
    const x = p === 0 ? 0 : Math.min(1, Math.max(0.15, (Math.log10(p) + 2) / 3));
    const hue = Math.round(120 - 120 * x), light = p === 0 ? 93 : 80;
    td.style.background = `hsl(${hue} 70% ${light}%`.concat(String.fromCharCode(41));
  });
});
document.querySelectorAll("p > code").forEach(code => {
  if (/^echo '.*' \| linequad (replay|cells) /.test(code.textContent)) addCopyButton(code);
});
</script>
</body>
</html>
)";

} // namespace

namespace {

// Debian's cmark-gfm takes time quadratic in a table's width (seconds for a line of tens of
// thousands of cells): a report.md is bounded before it reaches it. linequad writes tables of
// under 30 columns; a line with more than 256 cell separators is no report of linequad's.
constexpr std::size_t most_cells = 256;
void check_table_widths(const std::string& markdown) {
    std::size_t line = 1, cells = 0;
    for (std::size_t i = 0; i < markdown.size(); ++i) {
        char c = markdown[i];
        if (c == '\n') {
            ++line, cells = 0;
        } else if (c == '\\') {
            ++i; // an escaped character is no separator
        } else if (c == '|' && ++cells > most_cells) {
            throw std::runtime_error("report.md line " + std::to_string(line) +
                                     ": a table row of more than " + std::to_string(most_cells) +
                                     " cells (linequad writes none; refused rather than rendered)");
        }
    }
}

} // namespace

std::string
report_html(const std::string& markdown,
            const std::function<std::optional<std::string>(const std::string&)>& figure) {
    check_table_widths(markdown);
    cmark_gfm_core_extensions_ensure_registered();
    Document doc;
    doc.parser = cmark_parser_new(CMARK_OPT_DEFAULT);
    if (!doc.parser) throw std::bad_alloc();
    cmark_syntax_extension* table = cmark_find_syntax_extension("table");
    if (!table) throw std::logic_error("cmark-gfm has no table extension");
    cmark_parser_attach_syntax_extension(doc.parser, table);
    cmark_parser_feed(doc.parser, markdown.data(), markdown.size());
    doc.root = cmark_parser_finish(doc.parser);
    if (!doc.root) throw std::bad_alloc();

    // Raw HTML becomes text, links lose their targets, figures become data: URIs (or a note where
    // one was not drawn).
    std::vector<cmark_node*> missing;
    cmark_iter* it = cmark_iter_new(doc.root);
    for (cmark_event_type ev; (ev = cmark_iter_next(it)) != CMARK_EVENT_DONE;) {
        cmark_node* node = cmark_iter_get_node(it);
        cmark_node_type type = cmark_node_get_type(node);
        if ((type == CMARK_NODE_HTML_INLINE || type == CMARK_NODE_HTML_BLOCK) &&
            ev == CMARK_EVENT_ENTER) {
            const char* raw = cmark_node_get_literal(node);
            cmark_node_set_literal(node, jsonl::markup_text(raw ? raw : "").c_str());
        } else if (type == CMARK_NODE_LINK && ev == CMARK_EVENT_ENTER) {
            // A report links nowhere but into itself (its contents, to a section's anchor); a
            // javascript: URL would run.
            const char* url = cmark_node_get_url(node);
            cmark_node_set_url(node, within_page(url ? url : "") ? url : "");
        } else if (type == CMARK_NODE_IMAGE && ev == CMARK_EVENT_ENTER) {
            const char* url = cmark_node_get_url(node);
            std::string name = url ? url : "";
            const char* media = media_type(name);
            std::optional<std::string> bytes;
            if (media) bytes = figure(name);
            if (bytes)
                cmark_node_set_url(
                    node, ("data:" + std::string(media) + ";base64," + base64(*bytes)).c_str());
            else
                missing.push_back(node);
        }
    }
    cmark_iter_free(it);
    for (cmark_node* image : missing) {
        const char* url = cmark_node_get_url(image);
        cmark_node* note = cmark_node_new(CMARK_NODE_EMPH);
        cmark_node* text = cmark_node_new(CMARK_NODE_TEXT);
        cmark_node_set_literal(text, ("figure " + std::string(url ? url : "") +
                                      " not drawn (run the audit without --no-plots)")
                                         .c_str());
        cmark_node_append_child(note, text);
        cmark_node_replace(image, note);
        cmark_node_free(image);
    }

    // Unsafe only in name: no raw HTML is left, and the only URLs are the figures' data: URIs
    // (CMARK_OPT_SAFE would drop those: it allows no SVG data).
    char* body = cmark_render_html(doc.root, CMARK_OPT_UNSAFE,
                                   cmark_parser_get_syntax_extensions(doc.parser));
    if (!body) throw std::bad_alloc();
    std::string page = head;
    page += sectioned(body);
    page += tail;
    cmark_get_default_mem_allocator()->free(body);
    return page;
}

// A file of the report's own: a regular file in its directory, opened without following a
// symbolic link (a link there could point at any file, whose bytes would then be put in the
// page), at most 32 MiB.
std::optional<std::string> read_own_file(const std::string& dir, const std::string& name) {
    int fd = ::open((dir + "/" + name).c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) return std::nullopt;
    struct stat st {};
    std::optional<std::string> out;
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size <= (32 << 20)) {
        std::string bytes(std::size_t(st.st_size), '\0');
        std::size_t got = 0;
        while (got < bytes.size()) {
            ssize_t n = ::read(fd, bytes.data() + got, bytes.size() - got);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) break;
            got += std::size_t(n);
        }
        if (got == bytes.size()) out = std::move(bytes);
    }
    ::close(fd);
    return out;
}

void write_report_html(const std::string& dir) {
    std::optional<std::string> markdown = read_own_file(dir, "report.md");
    if (!markdown)
        throw std::runtime_error(dir + "/report.md: not a report's own file (missing, a link, "
                                       "or larger than 32 MiB)");
    auto figure = [&](const std::string& name) { return read_own_file(dir, name); };
    jsonl::write_file(dir + "/report.html", report_html(*markdown, figure));
}

} // namespace linequad::audit
