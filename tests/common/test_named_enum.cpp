// common/named_enum.hpp: one {value, name} table per enum serves the name, the parser (with
// aliases) and the lists that help texts and error messages print.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "common/named_enum.hpp"

namespace gradem::test_enum {
enum class Fruit { apple, pear, quince };
constexpr EnumNameTable<Fruit, 4> enum_name_table(Fruit) {
    return {{{Fruit::apple, "apple"}, {Fruit::pear, "pear"}, {Fruit::quince, "quince"}, {Fruit::pear, "poire"}}};
}
}  // namespace gradem::test_enum

using gradem::test_enum::Fruit;

TEST_CASE("named enum: names, parsing with aliases, and the lists", "[common]") {
    using namespace gradem;
    static_assert(NamedEnum<Fruit>);
    static_assert(parse_enum<Fruit>("quince") == Fruit::quince);
    CHECK(std::string(to_string(Fruit::pear)) == "pear");
    CHECK(std::string(to_string(static_cast<Fruit>(7))) == "unknown");
    CHECK(parse_enum<Fruit>("poire") == Fruit::pear);
    CHECK_FALSE(parse_enum<Fruit>("Pear"));
    CHECK(enum_names<Fruit>() == std::vector<std::string>{"apple", "pear", "quince"});
    CHECK(enum_names_text<Fruit>() == "apple, pear, quince");
    CHECK(enum_names_text<Fruit>(NameList::comma_or) == "apple, pear or quince");
    CHECK(enum_names_text<Fruit>(NameList::quoted_or) == "\"apple\", \"pear\" or \"quince\"");
    CHECK(enum_names_text<Fruit>(NameList::bar) == "apple|pear|quince");
}
