#include "linequad/json.hpp"

#include <cstdio>

namespace linequad::json {

const Value* Value::find(std::string_view key) const {
    for (const auto& m : members)
        if (m.first == key) return &m.second;
    return nullptr;
}

namespace {

class Parser {
  public:
    explicit Parser(std::string_view s) : s_(s) {}

    bool document(Value* v, std::string* error) {
        skip_space();
        if (!value(v, 0)) return fail(error);
        skip_space();
        if (pos_ != s_.size()) {
            why_ = "unexpected text after the value";
            return fail(error);
        }
        return true;
    }

  private:
    static constexpr int max_depth = 64; // a hostile file cannot exhaust the stack

    bool fail(std::string* error) {
        if (error) *error = why_ + " at column " + std::to_string(pos_ + 1);
        return false;
    }
    bool error(const char* why) {
        why_ = why;
        return false;
    }
    void skip_space() {
        while (pos_ < s_.size() &&
               (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\r' || s_[pos_] == '\n'))
            ++pos_;
    }
    bool literal(std::string_view word) {
        if (s_.substr(pos_, word.size()) != word) return error("invalid literal");
        pos_ += word.size();
        return true;
    }
    bool value(Value* v, int depth) {
        if (depth > max_depth) return error("nesting too deep");
        if (pos_ >= s_.size()) return error("unexpected end of line");
        char c = s_[pos_];
        switch (c) {
        case '{':
            return object(v, depth);
        case '[':
            return array(v, depth);
        case '"':
            v->type = Value::Type::string;
            return string(&v->text);
        case 't':
            v->type = Value::Type::boolean, v->boolean = true;
            return literal("true");
        case 'f':
            v->type = Value::Type::boolean, v->boolean = false;
            return literal("false");
        case 'n':
            v->type = Value::Type::null;
            return literal("null");
        default:
            return number(v);
        }
    }
    bool number(Value* v) {
        std::size_t start = pos_;
        if (pos_ < s_.size() && s_[pos_] == '-') ++pos_;
        auto digits = [&] {
            std::size_t d = pos_;
            while (pos_ < s_.size() && s_[pos_] >= '0' && s_[pos_] <= '9')
                ++pos_;
            return pos_ > d;
        };
        if (!digits()) return error("expected a value");
        if (pos_ < s_.size() && s_[pos_] == '.') {
            ++pos_;
            if (!digits()) return error("expected digits after '.'");
        }
        if (pos_ < s_.size() && (s_[pos_] == 'e' || s_[pos_] == 'E')) {
            ++pos_;
            if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
            if (!digits()) return error("expected digits in the exponent");
        }
        v->type = Value::Type::number;
        v->text.assign(s_.substr(start, pos_ - start));
        return true;
    }
    bool string(std::string* out) {
        ++pos_; // opening quote
        out->clear();
        while (pos_ < s_.size()) {
            char c = s_[pos_++];
            if (c == '"') return true;
            if (static_cast<unsigned char>(c) < 0x20) return error("control character in a string");
            if (c != '\\') {
                out->push_back(c);
                continue;
            }
            if (pos_ >= s_.size()) break;
            char e = s_[pos_++];
            switch (e) {
            case '"':
            case '\\':
            case '/':
                out->push_back(e);
                break;
            case 'b':
                out->push_back('\b');
                break;
            case 'f':
                out->push_back('\f');
                break;
            case 'n':
                out->push_back('\n');
                break;
            case 'r':
                out->push_back('\r');
                break;
            case 't':
                out->push_back('\t');
                break;
            case 'u': {
                if (pos_ + 4 > s_.size()) return error("short \\u escape");
                unsigned code = 0;
                for (int i = 0; i < 4; ++i) {
                    char h = s_[pos_++];
                    code <<= 4;
                    if (h >= '0' && h <= '9')
                        code |= h - '0';
                    else if (h >= 'a' && h <= 'f')
                        code |= h - 'a' + 10;
                    else if (h >= 'A' && h <= 'F')
                        code |= h - 'A' + 10;
                    else
                        return error("bad \\u escape");
                }
                // UTF-8 for the basic plane; ids and names need nothing more.
                if (code < 0x80)
                    out->push_back(char(code));
                else if (code < 0x800) {
                    out->push_back(char(0xC0 | (code >> 6)));
                    out->push_back(char(0x80 | (code & 0x3F)));
                } else {
                    out->push_back(char(0xE0 | (code >> 12)));
                    out->push_back(char(0x80 | ((code >> 6) & 0x3F)));
                    out->push_back(char(0x80 | (code & 0x3F)));
                }
                break;
            }
            default:
                return error("bad escape in a string");
            }
        }
        return error("unterminated string");
    }
    bool array(Value* v, int depth) {
        v->type = Value::Type::array;
        ++pos_;
        skip_space();
        if (pos_ < s_.size() && s_[pos_] == ']') return ++pos_, true;
        for (;;) {
            v->items.emplace_back();
            skip_space();
            if (!value(&v->items.back(), depth + 1)) return false;
            skip_space();
            if (pos_ < s_.size() && s_[pos_] == ',') {
                ++pos_;
                continue;
            }
            if (pos_ < s_.size() && s_[pos_] == ']') return ++pos_, true;
            return error("expected ',' or ']'");
        }
    }
    bool object(Value* v, int depth) {
        v->type = Value::Type::object;
        ++pos_;
        skip_space();
        if (pos_ < s_.size() && s_[pos_] == '}') return ++pos_, true;
        for (;;) {
            skip_space();
            if (pos_ >= s_.size() || s_[pos_] != '"') return error("expected a field name");
            std::string key;
            if (!string(&key)) return false;
            if (v->find(key)) return error("duplicate field");
            skip_space();
            if (pos_ >= s_.size() || s_[pos_] != ':') return error("expected ':'");
            ++pos_;
            skip_space();
            v->members.emplace_back(std::move(key), Value{});
            if (!value(&v->members.back().second, depth + 1)) return false;
            skip_space();
            if (pos_ < s_.size() && s_[pos_] == ',') {
                ++pos_;
                continue;
            }
            if (pos_ < s_.size() && s_[pos_] == '}') return ++pos_, true;
            return error("expected ',' or '}'");
        }
    }

    std::string_view s_;
    std::size_t pos_ = 0;
    std::string why_;
};

} // namespace

bool parse(std::string_view in, Value* out, std::string* error) {
    *out = Value{};
    return Parser(in).document(out, error);
}

void write_string(std::string& out, std::string_view s) {
    out.push_back('"');
    for (char c : s) {
        switch (c) {
        case '"':
            out += "\\\"";
            break;
        case '\\':
            out += "\\\\";
            break;
        case '\n':
            out += "\\n";
            break;
        case '\r':
            out += "\\r";
            break;
        case '\t':
            out += "\\t";
            break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "\\u%04x", c);
                out += buf;
            } else {
                out.push_back(c);
            }
        }
    }
    out.push_back('"');
}

void write(std::string& out, const Value& v) {
    switch (v.type) {
    case Value::Type::null:
        out += "null";
        break;
    case Value::Type::boolean:
        out += v.boolean ? "true" : "false";
        break;
    case Value::Type::number:
        out += v.text;
        break;
    case Value::Type::string:
        write_string(out, v.text);
        break;
    case Value::Type::array:
        out.push_back('[');
        for (std::size_t i = 0; i < v.items.size(); ++i) {
            if (i) out.push_back(',');
            write(out, v.items[i]);
        }
        out.push_back(']');
        break;
    case Value::Type::object:
        out.push_back('{');
        for (std::size_t i = 0; i < v.members.size(); ++i) {
            if (i) out.push_back(',');
            write_string(out, v.members[i].first);
            out.push_back(':');
            write(out, v.members[i].second);
        }
        out.push_back('}');
        break;
    }
}

} // namespace linequad::json
