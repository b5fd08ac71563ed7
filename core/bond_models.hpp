#pragma once
// THE list of bond laws. A law is one header, core/<law>_law.hpp (its kernel, its parameter
// struct and the rows describing each parameter; the interface is described at the top of
// core/bond_law.hpp), plus one row in GRADEM_BOND_LAWS below: LAW(name, Kernel), where `name` is
// the BondModel enumerator, the name configs, reports and the ledger use, and the macro.json
// group of the law's parameters. Everything else derives from this list: the BondModel enum
// and its names, the parameters BondParams holds (BondLawParams), the validator, the material
// table (experiments/config/material_table.cpp), the MPI wire format (calibrate/execution/run_message.cpp) and the
// analytic stand-in (calibrate/analytic_model.cpp).
// The World calls visit_bond_law once per phase, so each law's loop is compiled with its kernel
// inlined (no per-bond dispatch in the hot loop).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>

#include "common/named_enum.hpp"
#include "core/flat_joint_law.hpp"
#include "core/parallel_bond_law.hpp"
#include "core/soft_bond_law.hpp"

// clang-format off
#define GRADEM_BOND_LAWS(LAW)            \
    LAW(parallel_bond, ParallelBondLaw)  \
    LAW(soft_bond, SoftBondLaw)          \
    LAW(flat_joint, FlatJointLaw)
// clang-format on

namespace gradem {

#define GRADEM_BOND_LAW_ENUMERATOR(name, Law) name,
/// Which law the installed bonds follow: one enumerator per row of GRADEM_BOND_LAWS, in order
/// (the value is what the wire format and ParallelBond::model store).
enum class BondModel : std::uint8_t { GRADEM_BOND_LAWS(GRADEM_BOND_LAW_ENUMERATOR) };
#undef GRADEM_BOND_LAW_ENUMERATOR

namespace bond_registry_detail {
template <class First, class... Laws>
struct drop_first {
    using type = std::tuple<Laws...>;
};
template <class Law, class List>
struct index_of;
template <class Law, class... Laws>
struct index_of<Law, std::tuple<Laws...>> {
    static constexpr std::size_t value = [] {
        constexpr bool match[] = {std::is_same_v<Law, Laws>...};
        for (std::size_t k = 0; k < sizeof...(Laws); ++k)
            if (match[k]) return k;
        throw "not a registered bond law";
    }();
};
template <class List>
struct params_of;
template <class... Laws>
struct params_of<std::tuple<Laws...>> {
    using type = std::tuple<typename Laws::Params...>;
};
}  // namespace bond_registry_detail

#define GRADEM_BOND_LAW_TYPE(name, Law) , Law
/// The kernels, in BondModel order.
using BondLaws = bond_registry_detail::drop_first<void GRADEM_BOND_LAWS(GRADEM_BOND_LAW_TYPE)>::type;
#undef GRADEM_BOND_LAW_TYPE

inline constexpr std::size_t kBondLawCount = std::tuple_size_v<BondLaws>;

#define GRADEM_BOND_LAW_NAME(name, Law) #name,
/// The model names, in BondModel order ("parallel_bond", ...).
inline constexpr std::array<const char*, kBondLawCount> kBondModelNames = {GRADEM_BOND_LAWS(GRADEM_BOND_LAW_NAME)};
#undef GRADEM_BOND_LAW_NAME

#define GRADEM_BOND_LAW_NAME_ROW(name, Law) EnumName<BondModel>{BondModel::name, #name},
/// BondModel <-> name (common/named_enum.hpp: to_string, parse_enum<BondModel>, enum_names).
constexpr EnumNameTable<BondModel, kBondLawCount> enum_name_table(BondModel) {
    return {{GRADEM_BOND_LAWS(GRADEM_BOND_LAW_NAME_ROW)}};
}
#undef GRADEM_BOND_LAW_NAME_ROW

/// Every law's own parameter struct, in BondModel order (what BondParams::laws holds).
using BondLawParams = bond_registry_detail::params_of<BondLaws>::type;

/// The position of a law in the list (= its BondModel value).
template <class Law>
inline constexpr std::size_t bond_law_index = bond_registry_detail::index_of<Law, BondLaws>::value;
/// The BondModel a kernel implements.
template <class Law>
inline constexpr BondModel bond_model_of = static_cast<BondModel>(bond_law_index<Law>);

/// Calls visitor(Law{}) with the kernel of `model`; returns what the visitor returns.
template <class Visitor>
decltype(auto) visit_bond_law(BondModel model, Visitor&& visitor) {
#define GRADEM_BOND_LAW_CASE(name, Law) case BondModel::name: return visitor(Law{});
    switch (model) { GRADEM_BOND_LAWS(GRADEM_BOND_LAW_CASE) }
#undef GRADEM_BOND_LAW_CASE
    throw std::invalid_argument("visit_bond_law: unknown BondModel " + std::to_string(static_cast<int>(model)));
}

/// The law's PlatenTestCost row (core/law_parameters.hpp), if it states one.
inline std::optional<PlatenTestCost> platen_test_cost(BondModel model) {
    return visit_bond_law(model, [](auto kernel) -> std::optional<PlatenTestCost> {
        using Law = decltype(kernel);
        if constexpr (requires { Law::kPlatenTestCost; }) return Law::kPlatenTestCost;
        else return std::nullopt;
    });
}

/// Calls visitor(Law{}) for every law, in BondModel order (config and IO paths).
template <class Visitor>
void for_each_bond_law(Visitor&& visitor) {
    std::apply([&](auto... law) { (visitor(law), ...); }, BondLaws{});
}

}  // namespace gradem
