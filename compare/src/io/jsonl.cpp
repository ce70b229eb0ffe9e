#include "io/jsonl.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <iterator>
#include <new>
#include <stdexcept>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace linequad::jsonl {

namespace {

// An iterator over the text that records the furthest position nlohmann's lexer has read. The
// lexer reports a number after reading one character past it (or the end), so the position
// locates the token of a zero, whose sign the int64 value has lost.
struct TrackedIterator {
    using iterator_category = std::forward_iterator_tag;
    using value_type = char;
    using difference_type = std::ptrdiff_t;
    using pointer = const char*;
    using reference = const char&;

    const char* p = nullptr;
    const char** reached = nullptr;

    reference operator*() const { return *p; }
    TrackedIterator& operator++() {
        if (++p > *reached) *reached = p;
        return *this;
    }
    TrackedIterator operator++(int) {
        TrackedIterator old = *this;
        ++*this;
        return old;
    }
    bool operator==(const TrackedIterator& o) const { return p == o.p; }
    bool operator!=(const TrackedIterator& o) const { return p != o.p; }
};

// Builds the DOM as nlohmann's own SAX DOM parser does, refusing repeated keys and deep nesting.
class StrictBuilder : public nlohmann::json_sax<Json> {
  public:
    StrictBuilder(Json* root, const char* begin, const char* const* reached)
        : root_(root), begin_(begin), reached_(reached) {}

    std::string why;

    bool null() override { return put(nullptr); }
    bool boolean(bool b) override { return put(b); }
    bool number_integer(number_integer_t x) override {
        if (x == 0 && negative_zero()) return put(-0.0);
        return put(x);
    }
    bool number_unsigned(number_unsigned_t x) override {
        if (x == 0 && negative_zero()) return put(-0.0);
        return put(x);
    }
    bool number_float(number_float_t x, const string_t&) override { return put(x); }
    bool string(string_t& s) override { return put(std::move(s)); }
    bool binary(binary_t&) override { return fail("binary values are not JSON text"); }
    bool start_object(std::size_t) override {
        if (!put(Json::object())) return false;
        return open();
    }
    bool key(string_t& k) override {
        Json& object = *stack_.back();
        if (object.contains(k)) return fail("the field \"" + k + "\" appears twice");
        key_ = &object[k];
        return true;
    }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override {
        if (!put(Json::array())) return false;
        return open();
    }
    bool end_array() override { return close(); }
    bool parse_error(std::size_t position, const std::string&,
                     const nlohmann::detail::exception& e) override {
        // "[json.exception.parse_error.101] parse error at line 1, column 4: syntax error ..."
        std::string what = e.what();
        std::size_t tag = what.rfind("] ", what.find(' '));
        why = tag == std::string::npos ? what : what.substr(tag + 2);
        if (why.find("column") == std::string::npos)
            why += " at column " + std::to_string(position);
        return false;
    }

  private:
    bool fail(std::string message) {
        why = message + " at column " + std::to_string(*reached_ - begin_);
        return false;
    }
    bool negative_zero() const {
        // The token is -?[0-9]+ and ends at the reached position, or one character before it
        // when the lexer read past the token (that character cannot be a digit).
        const char* end = *reached_;
        if (end > begin_ && !(end[-1] >= '0' && end[-1] <= '9')) --end;
        const char* start = end;
        while (start > begin_ && start[-1] >= '0' && start[-1] <= '9')
            --start;
        return start > begin_ && start[-1] == '-' && end - start >= 1;
    }
    template <class V>
    bool put(V&& v) {
        if (stack_.empty()) {
            *root_ = Json(std::forward<V>(v));
            last_ = root_;
        } else if (stack_.back()->is_array()) {
            stack_.back()->push_back(Json(std::forward<V>(v)));
            last_ = &stack_.back()->back();
        } else {
            *key_ = Json(std::forward<V>(v));
            last_ = key_;
        }
        return true;
    }
    bool open() {
        if (int(stack_.size()) >= max_depth)
            return fail("nesting deeper than " + std::to_string(max_depth) + " levels");
        stack_.push_back(last_);
        return true;
    }
    bool close() {
        stack_.pop_back();
        return true;
    }

    Json* root_;
    const char* begin_;
    const char* const* reached_;
    std::vector<Json*> stack_;
    Json* key_ = nullptr;
    Json* last_ = nullptr;
};

} // namespace

bool parse(std::string_view text, Json* out, std::string* why) {
    *out = Json();
    // nlohmann's lexer takes a NUL for the end of its input: the rest of the line would be
    // dropped without a word. A NUL is no JSON text anywhere.
    if (std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
        *why = "a NUL byte at byte " + std::to_string(nul + 1) + " (JSON holds none)";
        return false;
    }
    const char* begin = text.data();
    const char* reached = begin;
    StrictBuilder builder(out, begin, &reached);
    TrackedIterator first{begin, &reached}, last{begin + text.size(), &reached};
    bool ok = false;
    try {
        ok = Json::sax_parse(first, last, &builder);
    } catch (const std::bad_alloc&) {
        release(*out); // then its reader names what it was reading
        throw;
    }
    if (!ok) {
        *out = Json();
        *why = builder.why.empty() ? "not valid JSON" : builder.why;
    }
    return ok;
}

void release(Json& v) noexcept {
    if (v.is_array()) {
        auto& items = v.get_ref<Json::array_t&>();
        for (Json& item : items)
            release(item);
        items.clear();
    } else if (v.is_object()) {
        auto& members = v.get_ref<Json::object_t&>();
        for (auto& member : members)
            release(member.second);
        members.clear();
    }
}

std::string dump(const Json& v) {
    return v.dump(-1, ' ', false, Json::error_handler_t::replace);
}
std::string dump(const OrderedJson& v) {
    return v.dump(-1, ' ', false, OrderedJson::error_handler_t::replace);
}

LineReader::LineReader(const std::string& path, std::size_t max_bytes) : max_(max_bytes) {
    if (path == "-") {
        file_ = stdin;
        name_ = "standard input";
        return;
    }
    name_ = path;
    file_ = std::fopen(path.c_str(), "rb");
    if (!file_) error_ = "cannot open '" + path + "': " + std::strerror(errno);
    owned_ = file_ != nullptr;
}

LineReader::~LineReader() {
    if (owned_) std::fclose(file_);
}

int LineReader::get() {
    if (stop_ && stop_->load(std::memory_order_relaxed)) {
        error_ = "stopped while reading '" + name_ + "'";
        return EOF;
    }
    int c = getc_unlocked(file_); // one reader per file: no locking needed
    if (c == EOF && std::ferror(file_))
        error_ = "cannot read '" + name_ + "': " + std::strerror(errno);
    return c;
}

LineReader::Status LineReader::next(std::string* out) {
    if (!file_ || !error_.empty()) return Status::error;
    out->clear();
    int c = get();
    if (c == EOF) return error_.empty() ? Status::end : Status::error;
    ++number_;
    bool too_long = false;
    for (; c != EOF && c != '\n'; c = get()) {
        if (too_long) continue;
        if (out->size() >= max_) {
            too_long = true;
            out->clear();
            out->shrink_to_fit();
            continue;
        }
        out->push_back(char(c));
    }
    if (!error_.empty()) return Status::error;
    if (!out->empty() && out->back() == '\r') out->pop_back();
    return too_long ? Status::too_long : Status::line;
}

std::string markup_text(std::string_view s) {
    std::string out;
    for (char c : s) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '>':
            out += "&gt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            if (static_cast<unsigned char>(c) >= 0x20 || c == '\n' || c == '\t') out += c;
        }
    }
    return out;
}

std::string too_long_message(long line, std::size_t max_bytes) {
    return "line " + std::to_string(line) + " is longer than the limit of " +
           std::to_string(max_bytes) + " bytes (--max-line-bytes)";
}

std::string read_file(const std::string& path, std::size_t max_bytes, const char* option) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno));
    std::string out;
    char buf[1 << 16];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) {
        if (n > max_bytes - out.size()) {
            std::fclose(f);
            throw std::runtime_error(path + " is larger than " + std::to_string(max_bytes) +
                                     " bytes (" + option + ")");
        }
        out.append(buf, n);
    }
    bool failed = std::ferror(f);
    int err = errno;
    std::fclose(f);
    if (failed) throw std::runtime_error("cannot read " + path + ": " + std::strerror(err));
    return out;
}

namespace {

// A scanner over JSON text already known to be valid: it finds where tokens end and never reads
// past the end, whatever it is given.
struct Scan {
    std::string_view t;
    std::size_t i = 0;
    bool ok = true;

    void space() {
        while (i < t.size() && (t[i] == ' ' || t[i] == '\t' || t[i] == '\n' || t[i] == '\r'))
            ++i;
    }
    bool take(char c) {
        space();
        if (i < t.size() && t[i] == c) return ++i, true;
        return false;
    }
    // A string token from its opening quote; *decoded gets its value (for keys).
    void string(std::string* decoded) {
        if (i >= t.size() || t[i] != '"') return void(ok = false);
        for (++i; i < t.size() && t[i] != '"'; ++i) {
            if (t[i] != '\\') {
                if (decoded) *decoded += t[i];
                continue;
            }
            if (++i >= t.size()) return void(ok = false);
            char e = t[i];
            if (e != 'u') {
                static const std::string_view from = "\"\\/bfnrt", to = "\"\\/\b\f\n\r\t";
                std::size_t k = from.find(e);
                if (k == std::string_view::npos) return void(ok = false);
                if (decoded) *decoded += to[k];
                continue;
            }
            // \uXXXX (a surrogate pair is two of them): the code point in UTF-8.
            auto hex4 = [&](std::size_t at, unsigned* out) {
                if (at + 4 > t.size()) return false;
                unsigned v = 0;
                for (std::size_t k = at; k < at + 4; ++k) {
                    char c = t[k];
                    int d = c >= '0' && c <= '9'   ? c - '0'
                            : c >= 'a' && c <= 'f' ? c - 'a' + 10
                            : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                                   : -1;
                    if (d < 0) return false;
                    v = v * 16 + unsigned(d);
                }
                *out = v;
                return true;
            };
            unsigned cp = 0;
            if (!hex4(i + 1, &cp)) return void(ok = false);
            i += 4;
            if (cp >= 0xD800 && cp <= 0xDBFF) {
                unsigned lo = 0;
                if (i + 2 < t.size() && t[i + 1] == '\\' && t[i + 2] == 'u' && hex4(i + 3, &lo) &&
                    lo >= 0xDC00 && lo <= 0xDFFF) {
                    cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
                    i += 6;
                }
            }
            if (!decoded) continue;
            if (cp < 0x80) {
                *decoded += char(cp);
            } else if (cp < 0x800) {
                *decoded += char(0xC0 | (cp >> 6));
                *decoded += char(0x80 | (cp & 0x3F));
            } else if (cp < 0x10000) {
                *decoded += char(0xE0 | (cp >> 12));
                *decoded += char(0x80 | ((cp >> 6) & 0x3F));
                *decoded += char(0x80 | (cp & 0x3F));
            } else {
                *decoded += char(0xF0 | (cp >> 18));
                *decoded += char(0x80 | ((cp >> 12) & 0x3F));
                *decoded += char(0x80 | ((cp >> 6) & 0x3F));
                *decoded += char(0x80 | (cp & 0x3F));
            }
        }
        if (i >= t.size()) return void(ok = false);
        ++i; // the closing quote
    }
    // Any value, appended to *out without the whitespace between its tokens.
    void value(std::string* out, int depth = 0) {
        space();
        if (i >= t.size() || depth > 64) return void(ok = false);
        std::size_t from = i;
        char c = t[i];
        if (c == '"') {
            string(nullptr);
            if (ok) out->append(t.substr(from, i - from));
        } else if (c == '{' || c == '[') {
            char close = c == '{' ? '}' : ']';
            *out += c;
            ++i;
            if (take(close)) return void(*out += close);
            for (bool first = true; ok; first = false) {
                if (!first) *out += ',';
                if (c == '{') {
                    space();
                    std::size_t k = i;
                    string(nullptr);
                    if (!ok) return;
                    out->append(t.substr(k, i - k));
                    if (!take(':')) return void(ok = false);
                    *out += ':';
                }
                value(out, depth + 1);
                if (take(close)) return void(*out += close);
                if (!take(',')) return void(ok = false);
            }
        } else {
            while (i < t.size() && t[i] != ',' && t[i] != '}' && t[i] != ']' && t[i] != ' ' &&
                   t[i] != '\t' && t[i] != '\n' && t[i] != '\r')
                ++i;
            if (i == from) return void(ok = false);
            out->append(t.substr(from, i - from));
        }
    }
};

} // namespace

std::string member_text(std::string_view text, std::string_view key) {
    Scan s{text};
    if (!s.take('{') || s.take('}')) return "";
    while (s.ok) {
        s.space();
        std::string name;
        s.string(&name);
        if (!s.ok || !s.take(':')) return "";
        std::string value;
        s.value(&value);
        if (!s.ok) return "";
        if (name == key) return value;
        if (!s.take(',')) return "";
    }
    return "";
}

void write_file(const std::string& path, std::string_view content) {
    auto failed = [&](const std::string& what, int err) {
        return std::runtime_error("cannot write " + what + ": " + std::strerror(err));
    };
    // Written through a temporary file and rename(), which replaces whatever the path names: only
    // where a regular file is or will be. A FIFO, a device, a socket or a link (to the standard
    // output, to another file) is refused, named, rather than replaced by a file.
    struct stat st {};
    if (::lstat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
        throw std::runtime_error(
            "cannot write " + path + ": " +
            (S_ISLNK(st.st_mode)    ? "a symbolic link (linequad replaces no link)"
             : S_ISFIFO(st.st_mode) ? "a FIFO (linequad writes its files whole, not to a pipe)"
             : S_ISDIR(st.st_mode)  ? "a directory"
                                    : "not a regular file (a device or a socket)"));
    std::string tmp = path + ".tmp." + std::to_string(::getpid());
    int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw failed(path, errno);
    const char* p = content.data();
    std::size_t left = content.size();
    while (left > 0) {
        ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            int err = n < 0 ? errno : EIO;
            ::close(fd);
            ::unlink(tmp.c_str());
            throw failed(path, err);
        }
        p += n, left -= std::size_t(n);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        int err = errno;
        ::unlink(tmp.c_str());
        throw failed(path, err);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        int err = errno;
        ::unlink(tmp.c_str());
        throw failed(path, err);
    }
}

Output::Output() {
    std::setvbuf(stdout, nullptr, _IOLBF, 1 << 16);
}

void Output::text(std::string_view t) {
    if (std::fwrite(t.data(), 1, t.size(), stdout) != t.size() || std::ferror(stdout))
        throw std::runtime_error(std::string("cannot write standard output: ") +
                                 std::strerror(errno));
}

void Output::line(std::string_view t) {
    text(t);
    text("\n");
}

void Output::finish() {
    if (std::fflush(stdout) != 0 || std::ferror(stdout))
        throw std::runtime_error(std::string("cannot write standard output: ") +
                                 std::strerror(errno));
}

void guard_standard_descriptors() {
    for (int fd = 0; fd <= 2; ++fd) {
        if (::fcntl(fd, F_GETFD) != -1 || errno != EBADF) continue;
        // Standard input opened for writing, the outputs for reading: any use fails (EBADF).
        int got = ::open("/dev/null", fd == 0 ? O_WRONLY : O_RDONLY);
        if (got >= 0 && got != fd) {
            ::dup2(got, fd);
            ::close(got);
        }
    }
}

} // namespace linequad::jsonl
