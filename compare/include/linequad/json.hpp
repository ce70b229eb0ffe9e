// A small JSON reader and writer, enough for the case and result formats (JSON Lines).
// Numbers keep their source text so that a decimal converts to the nearest double exactly once.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace linequad::json {

struct Value {
    enum class Type { null, boolean, number, string, array, object } type = Type::null;
    bool boolean = false;
    std::string text; // a number's source text, or a string's decoded contents
    std::vector<Value> items;
    std::vector<std::pair<std::string, Value>> members;

    const Value* find(std::string_view key) const;
};

// Parses one JSON document; on failure returns false and says why in *error.
bool parse(std::string_view in, Value* out, std::string* error);

// Appends s as a JSON string literal.
void write_string(std::string& out, std::string_view s);
// Writes a value back as compact JSON.
void write(std::string& out, const Value& v);

} // namespace linequad::json
