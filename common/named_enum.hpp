#pragma once
// Enum <-> name: the one place an enum's names are written is a table of {value, name} next to
// the enum, returned by a constexpr function `enum_name_table(E)` in the enum's namespace
// (found by argument-dependent lookup):
//
//   enum class Method { scaling, bobyqa };
//   constexpr EnumNameTable<Method, 2> enum_name_table(Method) {
//       return {{{Method::scaling, "scaling"}, {Method::bobyqa, "bobyqa"}}};
//   }
//
// Everything that turns such an enum into text or back goes through the functions below:
// to_string(value), parse_enum<E>(text), and enum_names<E>() / enum_names_text<E>(style) for
// help texts and error messages, so they list exactly the names the parser accepts.
// A value may appear in several rows: the first row is its name, the others are aliases that
// parse_enum accepts and the lists leave out.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace gradem {

template <class E>
struct EnumName {
    E value;
    const char* name;
};

template <class E, std::size_t N>
using EnumNameTable = std::array<EnumName<E>, N>;

/// An enum that has a name table.
template <class E>
concept NamedEnum = std::is_enum_v<E> && requires { enum_name_table(E{}); };

/// The name of `value` ("unknown" for a value outside the table).
template <NamedEnum E>
constexpr const char* to_string(E value) {
    for (const EnumName<E>& row : enum_name_table(E{}))
        if (row.value == value) return row.name;
    return "unknown";
}

/// The value named `name` (a name or an alias, exactly as written); nullopt for none.
template <NamedEnum E>
constexpr std::optional<E> parse_enum(std::string_view name) {
    for (const EnumName<E>& row : enum_name_table(E{}))
        if (name == row.name) return row.value;
    return std::nullopt;
}

/// Every value's name, in table order, without aliases.
template <NamedEnum E>
std::vector<std::string> enum_names() {
    std::vector<std::string> names;
    const auto table = enum_name_table(E{});
    for (std::size_t k = 0; k < table.size(); ++k) {
        bool alias = false;
        for (std::size_t j = 0; j < k; ++j) alias = alias || table[j].value == table[k].value;
        if (!alias) names.emplace_back(table[k].name);
    }
    return names;
}

/// How enum_names_text() joins the names.
enum class NameList {
    comma,      ///< a, b, c
    comma_or,   ///< a, b or c
    quoted_or,  ///< "a", "b" or "c" (error messages: `expected ...`)
    bar,        ///< a|b|c (usage lines)
};

/// The names of enum_names<E>() as one line for help texts and error messages.
template <NamedEnum E>
std::string enum_names_text(NameList style = NameList::comma) {
    const std::vector<std::string> names = enum_names<E>();
    std::string out;
    for (std::size_t k = 0; k < names.size(); ++k) {
        const bool last = k + 1 == names.size();
        const bool with_or = style == NameList::comma_or || style == NameList::quoted_or;
        if (k > 0) out += style == NameList::bar ? "|" : with_or && last ? " or " : ", ";
        out += style == NameList::quoted_or ? "\"" + names[k] + "\"" : names[k];
    }
    return out;
}

}  // namespace gradem
