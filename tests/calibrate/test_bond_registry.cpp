// The bond-law registry (core/bond_models.hpp) and what derives from it: every model name
// parses back, every law row is in the material table with the law's model bit and group and
// reaches the same field, the core validator enforces every row's range, and every row crosses
// the MPI wire format bit for bit.
#include <bit>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <set>
#include <string>

#include "calibrate/execution/run_message.hpp"
#include "core/bond_models.hpp"
#include "core/params.hpp"
#include "experiments/virtual_tests/cube_test.hpp"
#include "experiments/config/material_table.hpp"

using namespace gradem;

namespace {

/// A value of the row inside its range and different from `current` (config units).
template <class Row>
double other_value(const Row& row, double current) {
    if (row.field.flag) return current != 0.0 ? 0.0 : 1.0;
    const double lo = std::isfinite(row.range.lower) ? row.range.lower : 0.0;
    const double hi = std::isfinite(row.range.upper) ? row.range.upper : lo + 2.0;
    double v = row.field.integer ? std::floor(0.5 * (lo + hi)) + 1.0 : lo + (hi - lo) / 3.0;
    if (v == current) v = row.field.integer ? v - 1.0 : lo + (hi - lo) / 7.0;
    return v;
}

/// A value just outside the row's range, or NaN if every value of its type is inside.
template <class Row>
double outside_value(const Row& row) {
    if (row.field.flag) return std::nan("");
    if (std::isfinite(row.range.lower)) return row.range.lower_open ? row.range.lower : row.range.lower - 1.0;
    if (std::isfinite(row.range.upper)) return row.range.upper_open ? row.range.upper : row.range.upper + 1.0;
    return std::nan("");
}

}  // namespace

TEST_CASE("bond registry: every model name parses back, unknown names do not", "[bond_registry]") {
    REQUIRE(exp::bond_models().size() == kBondLawCount);
    std::set<std::string> names;
    for (std::size_t k = 0; k < kBondLawCount; ++k) {
        const auto model = static_cast<BondModel>(k);
        CHECK(exp::bond_models()[k] == model);
        const std::string name = bond_model_name(model);
        CHECK(parse_bond_model(name) == model);
        CHECK(names.insert(name).second);
        CHECK_THAT(exp::bond_model_names(), Catch::Matchers::Contains(name));
    }
    CHECK(bond_model_name(BondModel::parallel_bond) == std::string("parallel_bond"));
    CHECK(bond_model_of<ParallelBondLaw> == BondModel::parallel_bond);
    CHECK_FALSE(parse_bond_model("no_such_law"));
    CHECK(std::string(bond_model_name(static_cast<BondModel>(kBondLawCount))) == "unknown");
}

TEST_CASE("bond registry: every law row is a material-table row of that law alone", "[bond_registry]") {
    std::size_t law_rows = 0;
    for_each_bond_law([&](auto kernel) {
        using Law = decltype(kernel);
        const BondModel model = bond_model_of<Law>;
        for (const auto& row : Law::kParameters) {
            INFO(bond_model_name(model) << " row " << row.key);
            ++law_rows;
            const exp::MaterialParameter* p = exp::find_material_parameter(row.key);
            REQUIRE(p != nullptr);
            CHECK(p->models == exp::model_bit(model));
            CHECK(p->si_group == bond_model_name(model));
            CHECK(p->si_name == row.key);
            CHECK(p->core_field == row.core_field);
            CHECK(exp::material_parameter_of_field(row.core_field) == p);
            CHECK(p->integer == row.field.integer);
            CHECK(p->flag == row.field.flag);
            CHECK(p->in_config);
            CHECK(p->range.rule() == row.range.rule());
            CHECK(p->calibration == row.calibration);
            CHECK(p->role == ParameterRole::shape);
            // the table row and the law row reach the same field
            exp::MaterialParams m;
            const double before = row.field.get(m.bond.law<Law>());
            const double v = other_value(row, before);
            exp::set_config_value(*p, m, v);
            CHECK(row.field.get(m.bond.law<Law>()) == v * row.to_si);
            CHECK(exp::config_value(*p, m) == v);
            if (row.field.integer) CHECK(p->get_int(m) == static_cast<std::int64_t>(v));
            // and the model's table rows accept it
            m.bond.model = model;
            CHECK_FALSE(exp::material_range_violation(m));
        }
    });
    CHECK(law_rows >= 9);  // the soft bond's 2 and the flat joint's 7
    std::size_t table_law_rows = 0;
    for (const exp::MaterialParameter& p : exp::material_table())
        if (p.models != exp::kEveryModel && std::popcount(p.models) == 1 && !p.applies_to(BondModel::parallel_bond))
            ++table_law_rows;
    CHECK(table_law_rows == law_rows);  // no law row written out in the table by hand
}

TEST_CASE("bond registry: the core validator enforces every row's range", "[bond_registry]") {
    for_each_bond_law([&](auto kernel) {
        using Law = decltype(kernel);
        for (const auto& row : Law::kParameters) {
            const double bad = outside_value(row);
            if (std::isnan(bad)) continue;
            INFO(row.key << " = " << bad);
            BondParams b;
            REQUIRE_FALSE(b.invalid_reason());
            if (row.field.integer) row.field.set_int(b.law<Law>(), static_cast<std::int64_t>(bad));
            else row.field.set(b.law<Law>(), bad * row.to_si);
            const auto reason = b.invalid_reason();
            REQUIRE(reason);
            CHECK_THAT(*reason, Catch::Matchers::StartsWith(std::string(row.core_field) + " = "));
            CHECK_THAT(*reason, Catch::Matchers::EndsWith("violates " + row.range.rule()));
        }
    });
    BondParams fractions;
    fractions.law<FlatJointLaw>().bonded_fraction = 0.7;
    fractions.law<FlatJointLaw>().gapped_fraction = 0.4;
    CHECK(fractions.invalid_reason() ==
          "FlatJointParams::gapped_fraction = 0.4 violates <= 1 - FlatJointParams::bonded_fraction (the fractions sum to at most 1)");
}

TEST_CASE("bond registry: every law row crosses the wire format bit for bit", "[bond_registry]") {
    for_each_bond_law([&](auto kernel) {
        using Law = decltype(kernel);
        for (const auto& row : Law::kParameters) {
            INFO(bond_model_name(bond_model_of<Law>) << " row " << row.key);
            cal::wire::Run run;
            run.request.material.bond.model = bond_model_of<Law>;
            auto& own = run.request.material.bond.law<Law>();
            const double before = row.field.get(own);
            if (row.field.integer) row.field.set_int(own, static_cast<std::int64_t>(other_value(row, before)));
            else row.field.set(own, other_value(row, before) / 3.0);  // not a short decimal: bits matter
            const std::string bytes = cal::wire::encode(run);
            const cal::wire::Run back = cal::wire::decode_run(bytes);
            const auto& got = back.request.material.bond.law<Law>();
            CHECK(back.request.material.bond.model == bond_model_of<Law>);
            if (row.field.integer) CHECK(row.field.get_int(got) == row.field.get_int(own));
            else {
                const double x = row.field.get(own), y = row.field.get(got);
                CHECK(std::memcmp(&x, &y, sizeof x) == 0);
            }
            CHECK(row.field.get(got) != before);
            cal::wire::Run plain;
            plain.request.material.bond.model = bond_model_of<Law>;
            CHECK(cal::wire::encode(plain) != bytes);  // the row is in the message
        }
    });
}
