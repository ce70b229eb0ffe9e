// report.html: the audit's report.md as one self-contained page (no network: the figures inline,
// the styles and scripts in the file), with sortable tables and a copy button for each replay
// command. Rendered from report.md, so the two always say the same.
#pragma once

#include <functional>
#include <optional>
#include <string>

namespace linequad::audit {

// The page for a report's markdown. figure(name) returns the contents of a figure the markdown
// names (pareto.svg, ...), or nothing if it was not drawn: the page then says so in its place.
// Raw HTML in the markdown (a solver's name, say) is shown as text, never run.
std::string
report_html(const std::string& markdown,
            const std::function<std::optional<std::string>(const std::string&)>& figure);

// DIR/report.md and its figures to DIR/report.html (written atomically). Throws naming the file
// it cannot read or write.
void write_report_html(const std::string& dir);

} // namespace linequad::audit
