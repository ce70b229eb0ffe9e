// report.html from report.md: tables, figures inlined, raw HTML shown as text, no URL left that
// would leave the file. (html_report_test.sh opens a real report in Chromium.)
#include "report/report_html.hpp"

#include <catch2/catch.hpp>

#include <map>

using linequad::audit::report_html;

namespace {

std::string page(const std::string& markdown, const std::map<std::string, std::string>& files) {
    return report_html(markdown, [&](const std::string& name) -> std::optional<std::string> {
        auto it = files.find(name);
        if (it == files.end()) return std::nullopt;
        return it->second;
    });
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

} // namespace

TEST_CASE("report.html: tables, and figures inlined as base64 data", "[html]") {
    std::string md = "# t\n\n| a | b |\n|---|---:|\n| x | 1 |\n\n![p](p.svg)\n\n![q](q-1.svg)\n";
    // "foo" and "fo": base64's full group and its one-byte padding (RFC 4648's test vectors).
    std::string html = page(md, {{"p.svg", "foo"}, {"q-1.svg", "fo"}});
    CHECK(has(html, "<table>"));
    CHECK(has(html, "<td align=\"right\">1</td>"));
    CHECK(has(html, "src=\"data:image/svg+xml;base64,Zm9v\""));
    CHECK(has(html, "src=\"data:image/svg+xml;base64,Zm8=\""));
    CHECK(has(html, "Content-Security-Policy"));
}

TEST_CASE("report.html: only the report's own figures, by plain names, are inlined", "[html]") {
    // A path, a hidden file, another type or a scheme is never read, whatever figure() would say.
    for (const char* name :
         {"../x.svg", "/etc/x.svg", ".x.svg", "x.png", "file:x.svg", "a b.svg"}) {
        std::string html = page(std::string("![x](") + name + ")\n", {{name, "foo"}});
        INFO(name);
        CHECK_FALSE(has(html, "base64,Zm9v"));
    }
}

TEST_CASE("report.html: a figure not drawn is named in its place", "[html]") {
    std::string html = page("![pareto](pareto.svg)\n", {});
    CHECK(has(html, "figure pareto.svg not drawn"));
    CHECK_FALSE(has(html, "<img"));
}

TEST_CASE("report.html: raw HTML from a report is text, never markup", "[html]") {
    // A solver's name is the plugin's to choose; it reaches report.md as it is.
    std::string md = "| solver |\n|---|\n| <script>alert(1)</script> |\n\n<div onclick=x>\n\n"
                     "<img src=\"http://example.com/a.png\">\n";
    std::string html = page(md, {});
    CHECK(has(html, "&lt;script&gt;alert(1)&lt;/script&gt;"));
    CHECK_FALSE(has(html, "<script>alert"));
    CHECK_FALSE(has(html, "<div onclick"));
    CHECK_FALSE(has(html, "src=\"http"));
    // Nor a link: the page's CSP allows inline script, which a javascript: URL would be.
    std::string linked = page("| solver |\n|---|\n| [x](javascript:alert(1)) |\n", {});
    CHECK_FALSE(has(linked, "javascript:"));
}

TEST_CASE("report.html: a figure named by a path or a URL is not read", "[html]") {
    std::map<std::string, std::string> files{{"../secret.svg", "x"},
                                             {"http://example.com/a.svg", "x"}};
    std::string html = page("![a](../secret.svg)\n\n![b](http://example.com/a.svg)\n", files);
    CHECK_FALSE(has(html, "<img"));
    CHECK(has(html, "figure ../secret.svg not drawn"));
}
