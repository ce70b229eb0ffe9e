// A region's text, OpenMC's syntax, parsed by recursive descent into postfix tokens, and its
// three-valued evaluation.
#include "linequad/cells.hpp"

#include <cctype>
#include <cstdint>
#include <limits>

namespace linequad {

namespace {

// union := intersection ('|' intersection)*;  intersection := unary unary*;
// unary := '~' unary | '(' union ')' | ['+'|'-'] digits.
class Parser {
  public:
    explicit Parser(std::string_view text) : text_(text) {}

    bool parse(std::vector<Region::Token>& out, std::string& error) {
        out_ = &out;
        skip_space();
        if (at_end()) return fail("the region is empty", error);
        if (!union_(error)) return false;
        skip_space();
        if (!at_end()) {
            if (peek() == ')') return fail("a ')' without its '('", error);
            return fail(std::string("unexpected '") + peek() + "'", error);
        }
        return true;
    }

  private:
    // Nesting is recursion here: bounded, so that hostile text cannot exhaust the stack.
    static constexpr int max_depth = 1000;
    std::string_view text_;
    std::size_t at_ = 0;
    int depth_ = 0;
    std::vector<Region::Token>* out_ = nullptr;

    bool at_end() const { return at_ >= text_.size(); }
    char peek() const { return text_[at_]; }
    void skip_space() {
        while (!at_end() && std::isspace(static_cast<unsigned char>(peek())))
            ++at_;
    }
    bool fail(const std::string& what, std::string& error) const {
        error = what + " at column " + std::to_string(at_ + 1);
        return false;
    }
    // What can start a unary: a sign, a digit, '~' or '('.
    bool starts_unary() const {
        if (at_end()) return false;
        char c = peek();
        return c == '~' || c == '(' || c == '-' || c == '+' ||
               std::isdigit(static_cast<unsigned char>(c));
    }

    bool union_(std::string& error) {
        if (!intersection(error)) return false;
        for (skip_space(); !at_end() && peek() == '|'; skip_space()) {
            ++at_;
            skip_space();
            if (!starts_unary()) return fail("'|' with nothing after it", error);
            if (!intersection(error)) return false;
            out_->push_back({Region::Op::union_});
        }
        return true;
    }
    bool intersection(std::string& error) {
        if (!unary(error)) return false;
        for (skip_space(); starts_unary(); skip_space()) {
            if (!unary(error)) return false;
            out_->push_back({Region::Op::intersection});
        }
        return true;
    }
    bool unary(std::string& error) {
        skip_space();
        if (at_end()) return fail("the region ends where a surface or '(' was expected", error);
        char c = peek();
        if (c == '~') {
            if (++depth_ > max_depth) return fail("complements nested too deep", error);
            ++at_;
            if (!unary(error)) return false;
            --depth_;
            out_->push_back({Region::Op::complement});
            return true;
        }
        if (c == '(') {
            if (++depth_ > max_depth) return fail("parentheses nested too deep", error);
            std::size_t open = at_;
            ++at_;
            skip_space();
            if (!at_end() && peek() == ')') return fail("'()' holds no region", error);
            if (!union_(error)) return false;
            skip_space();
            if (at_end() || peek() != ')') {
                at_ = open;
                return fail("a '(' without its ')'", error);
            }
            ++at_, --depth_;
            return true;
        }
        return half_space(error);
    }
    bool half_space(std::string& error) {
        std::size_t start = at_;
        bool positive = true;
        if (peek() == '-' || peek() == '+') positive = peek() == '+', ++at_;
        if (at_end() || !std::isdigit(static_cast<unsigned char>(peek()))) {
            at_ = start;
            if (at_end()) return fail("the region ends where a surface was expected", error);
            return fail(std::string("unexpected '") + peek() + "'", error);
        }
        std::int64_t id = 0;
        for (; !at_end() && std::isdigit(static_cast<unsigned char>(peek())); ++at_) {
            int d = peek() - '0';
            if (id > (std::numeric_limits<std::int64_t>::max() - d) / 10) {
                at_ = start;
                return fail("a surface id too large", error);
            }
            id = id * 10 + d;
        }
        if (id == 0) {
            at_ = start;
            return fail("surface id 0 has no sign to give a side", error);
        }
        out_->push_back({Region::Op::half_space, positive, id});
        return true;
    }
};

// Kleene's three-valued logic: 0 false, 1 true, 2 undecided.
constexpr std::uint8_t no = 0, yes = 1, unknown = 2;

} // namespace

std::optional<Region> Region::parse(std::string_view text, std::string& error) {
    Region r;
    if (!Parser(text).parse(r.tokens_, error)) return std::nullopt;
    return r;
}

std::optional<bool> Region::contains(const std::vector<Sense>& senses) const {
    // A stack no deeper than the tokens; most regions hold a handful.
    std::vector<std::uint8_t> stack;
    stack.reserve(tokens_.size());
    for (const Token& t : tokens_) {
        switch (t.op) {
        case Op::half_space: {
            Sense s = senses[std::size_t(t.surface)];
            stack.push_back(s == Sense::on                         ? unknown
                            : (s == Sense::positive) == t.positive ? yes
                                                                   : no);
            break;
        }
        case Op::complement:
            if (stack.back() != unknown) stack.back() = stack.back() == yes ? no : yes;
            break;
        case Op::intersection:
        case Op::union_: {
            std::uint8_t b = stack.back();
            stack.pop_back();
            std::uint8_t& a = stack.back();
            bool both_and = t.op == Op::intersection;
            std::uint8_t absorbing = both_and ? no : yes; // false for and, true for or
            if (a == absorbing || b == absorbing)
                a = absorbing;
            else if (a == unknown || b == unknown)
                a = unknown;
            else
                a = both_and ? yes : no;
            break;
        }
        }
    }
    if (stack.back() == unknown) return std::nullopt;
    return stack.back() == yes;
}

} // namespace linequad
