// JSON Lines on nlohmann-json, made strict where the formats need it, and output that never
// fails silently.
//
// parse() refuses what nlohmann's DOM parser lets through: a repeated key (it keeps the last
// silently) and nesting deeper than a case or a report ever needs. It also keeps the sign of
// the JSON integer -0, which nlohmann reads into an int64 (no negative zero). LineReader bounds
// the memory one line can take, so a hostile line costs a named error and the next line is
// still read. write_file() and Output check every write.
#pragma once

#include <nlohmann/json.hpp>

#include <atomic>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>
#include <string_view>

namespace linequad::jsonl {

using Json = nlohmann::json;
using OrderedJson = nlohmann::ordered_json; // what we write: fields in the order people read them

inline constexpr int max_depth = 32;
inline constexpr std::size_t default_max_line_bytes = std::size_t(1) << 20;

// Parses one JSON document. On failure returns false with *why naming the problem and the column.
bool parse(std::string_view text, Json* out, std::string* why);

// The text of the value of `key`, a member of the JSON object `text` (already parsed, so known to
// be JSON), exactly as written there but for the whitespace between its tokens: a number keeps
// every digit (2^64 + 1 is not read as a double), a string its escapes. Empty when `text` is not
// an object or has no such member. What ids are kept as: echoed back as they came.
std::string member_text(std::string_view text, std::string_view key);

// Empties a value from its leaves up without allocating. nlohmann's destructor flattens an array
// or object into a stack it allocates (as large as the container): a value destroyed while a
// std::bad_alloc unwinds needs memory there is none of, and std::terminate ends the process.
// Recursion is bounded by max_depth for what parse() built.
void release(Json& v) noexcept;

// Releases a value when an exception leaves its scope (declared after it, so destroyed first).
class ReleaseOnUnwind {
  public:
    explicit ReleaseOnUnwind(Json& v) : v_(v), unwinding_(std::uncaught_exceptions()) {}
    ~ReleaseOnUnwind() {
        if (std::uncaught_exceptions() > unwinding_) release(v_);
    }
    ReleaseOnUnwind(const ReleaseOnUnwind&) = delete;
    ReleaseOnUnwind& operator=(const ReleaseOnUnwind&) = delete;

  private:
    Json& v_;
    int unwinding_;
};

// Compact JSON text of a value; bytes that are not UTF-8 (which only our own messages can carry:
// the parser refuses them in input) become U+FFFD, so the output is always JSON.
std::string dump(const Json& v);
std::string dump(const OrderedJson& v);

// Reads a file (or standard input) line by line, holding at most max_bytes of any one line.
class LineReader {
  public:
    enum class Status { line, too_long, end, error };

    // path "-" is standard input. A file that cannot be opened is reported by the first next().
    LineReader(const std::string& path, std::size_t max_bytes = default_max_line_bytes);
    ~LineReader();
    LineReader(const LineReader&) = delete;
    LineReader& operator=(const LineReader&) = delete;

    // line: *out holds the line (no newline). too_long: the line was skipped (the next call
    // reads the one after it). end: no more input. error: a read failed; error() says why.
    Status next(std::string* out);
    // A flag that, once set (a stop request), ends reading as an error ("stopped"), even inside
    // an endless line.
    void stop_when(const std::atomic<bool>* flag) { stop_ = flag; }
    long number() const { return number_; } // of the line last returned, from 1
    const std::string& error() const { return error_; }
    const std::string& name() const { return name_; } // the path, or "standard input"

  private:
    int get();
    std::FILE* file_ = nullptr;
    bool owned_ = false;
    std::string name_, error_;
    std::size_t max_;
    long number_ = 0;
    const std::atomic<bool>* stop_ = nullptr;
};

// A line of spaces and tabs only: JSON Lines readers skip it.
inline bool blank(std::string_view line) {
    return line.find_first_not_of(" \t\r") == std::string_view::npos;
}

// Text made safe inside XML or HTML, in an element or a quoted attribute: & < > " escaped, and
// the control characters XML 1.0 forbids even escaped left out.
std::string markup_text(std::string_view s);

// "line 12 is longer than the limit of 1048576 bytes (--max-line-bytes)"
std::string too_long_message(long line, std::size_t max_bytes);

// The whole of a file, at most max_bytes of it; throws std::runtime_error naming the path and
// the reason (a file larger than that named so, `option` saying which option sets the bound).
std::string read_file(const std::string& path, std::size_t max_bytes = std::size_t(-1),
                      const char* option = "");

// Writes content to path through a temporary file in the same directory, synced and renamed,
// so that a reader (or a crash) never sees half a file. Throws std::runtime_error naming the
// path and the reason on any failure.
void write_file(const std::string& path, std::string_view content);

// Standard output, every write checked: the first failure throws std::runtime_error naming
// "standard output" and the reason (a full disk, a closed descriptor).
class Output {
  public:
    Output(); // line buffered: a long run that is stopped keeps every line it wrote
    void line(std::string_view text); // text and a newline
    void text(std::string_view text);
    void finish(); // flushes; throws on failure
};

// If a standard descriptor (0, 1, 2) is closed, opens /dev/null on it in the direction that
// makes every use fail: a file opened later cannot take its number and receive our output, and
// writing to a closed standard output is still an error rather than silence.
void guard_standard_descriptors();

// Every line of `in` that is not blank, to on_line(line, parse) where parse(f) runs the parser
// f() (true when the line reads) and turns running out of memory into a false with *why said;
// a line over the limit to on_too_long(message). A read error throws naming the input.
template <class OnLine, class OnTooLong>
void each_line(LineReader& in, std::size_t max_bytes, std::string* why, OnLine&& on_line,
               OnTooLong&& on_too_long) {
    std::string line;
    for (;;) {
        auto status = in.next(&line);
        if (status == LineReader::Status::end) return;
        if (status == LineReader::Status::error) throw std::runtime_error(in.error());
        if (status == LineReader::Status::too_long) {
            on_too_long(too_long_message(in.number(), max_bytes));
            continue;
        }
        if (blank(line)) continue;
        auto parse = [&](auto&& f) {
            try {
                return bool(f());
            } catch (const std::bad_alloc&) {
                *why = "out of memory while reading it";
                return false;
            }
        };
        on_line(line, parse);
    }
}

} // namespace linequad::jsonl
