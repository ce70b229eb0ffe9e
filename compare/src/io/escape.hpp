// Text from outside (solver, family and plugin names, paths, a library's own words) made safe for
// each place it lands: one function per place, each tested against the characters that would
// break it (tests/test_escape.cpp). XML and HTML text is jsonl::markup_text.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace linequad::escape {

// One POSIX shell word: in single quotes, each ' as '\'' (no shell expands anything in it).
std::string shell_word(std::string_view s);

// Markdown inline text (a paragraph, a heading, a table cell): every ASCII punctuation mark
// backslash-escaped, as CommonMark allows for any of them (so no *, _, `, |, <, & or [ acts),
// and line breaks and other control characters as spaces. It renders as the characters it holds.
std::string markdown_text(std::string_view s);

// A markdown code span: fenced by one backtick more than the longest run it holds, padded where
// it starts or ends with one, line breaks as spaces. Not for table cells (a | there ends the cell
// even inside a code span): use markdown_text.
std::string markdown_code(std::string_view s);

// A fenced code block of these lines, each line and fence after `indent`: the fence is longer
// than any run of backticks in the lines, and a line break inside a line becomes a space.
std::string markdown_block(const std::vector<std::string>& lines, std::string_view indent = "");

// A name as part of a file name: letters, digits and _ kept, every other byte as -XX (two hex
// digits), so that distinct names give distinct files and no name gives a path; beyond 80
// characters, cut and ended with a hash of the whole.
std::string file_name(std::string_view s);

// A heading's anchor in report.html, from its text as a person reads it: lowercase letters and
// digits kept, every run of anything else one '-', none at either end ("Solver: seed32" is
// "solver-seed32"). The report's contents link to it; report.html gives its sections that id.
std::string anchor(std::string_view s);

// linequad's own markdown (a diff, a trend) as plain text for a terminal: backslash escapes,
// bold marks and code-span backticks dropped, tables as columns padded to their widest cell, the
// header's rule a line of dashes.
std::string markdown_as_text(std::string_view md);

} // namespace linequad::escape
