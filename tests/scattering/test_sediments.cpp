// Sediment parameters of the APL-UW model: the TR 9407 Table 2 presets, lookup by name, the grain-size
// regressions behind the table, and validation.

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sss/scattering/sediments.hpp>

using namespace sss::scattering;

namespace {

// Half a unit in the last printed digit of a Table 2 entry (the rows print 4 or 5 significant digits).
double half_unit_of_print(int decimals) { return 0.5 * std::pow(10.0, -decimals) * (1.0 + 1e-9); }

struct printed_row {
    sediment id;
    double mz_phi;
    double rho;
    int rho_dec;
    double nu;
    int nu_dec;
    double delta;
    int delta_dec;
    double sigma2;
    double w2;
    int w2_dec;
};

// TR 9407 Table 2 as printed, with the number of decimals each entry shows.
const printed_row table2[] = {
    {sediment::sandy_gravel, -1.0, 2.492, 3, 1.337, 3, 0.01705, 5, 0.002, 0.012937, 6},
    {sediment::very_coarse_sand, -0.5, 2.401, 3, 1.3067, 4, 0.01667, 5, 0.002, 0.010573, 6},
    {sediment::coarse_sand, 0.5, 2.231, 3, 1.2503, 4, 0.01638, 5, 0.002, 0.006957, 6},
    {sediment::medium_sand, 1.5, 1.845, 3, 1.1782, 4, 0.01624, 5, 0.002, 0.004446, 6},
    {sediment::fine_sand, 2.5, 1.451, 3, 1.1073, 4, 0.01602, 5, 0.002, 0.002715, 6},
    {sediment::very_fine_sand, 3.5, 1.268, 3, 1.0568, 4, 0.01875, 5, 0.002, 0.001544, 6},
    {sediment::coarse_silt, 4.5, 1.195, 3, 1.0179, 4, 0.02158, 5, 0.002, 0.000781, 6},
    {sediment::sandy_silt, 5.0, 1.169, 3, 0.9999, 4, 0.01261, 5, 0.002, 0.000518, 6},
    {sediment::sandy_mud, 6.0, 1.149, 3, 0.9873, 4, 0.00386, 5, 0.001, 0.000518, 6},
    {sediment::sandy_clay, 7.0, 1.147, 3, 0.9849, 4, 0.00242, 5, 0.001, 0.000518, 6},
    {sediment::silty_clay, 8.0, 1.146, 3, 0.9824, 4, 0.00163, 5, 0.001, 0.000518, 6},
    {sediment::clay, 9.0, 1.145, 3, 0.9800, 4, 0.00148, 5, 0.001, 0.000518, 6},
};

} // namespace

TEST_CASE("TR 9407 Table 2 presets carry the printed parameters") {
    const auto ms = sediment_preset<double>(sediment::medium_sand);
    CHECK(ms.rho == 1.845);
    CHECK(ms.nu == 1.1782);
    CHECK(ms.delta == 0.01624);
    CHECK(ms.sigma2 == 0.002);
    CHECK(ms.gamma == 3.25);
    CHECK(ms.w2_cm4 == 0.004446);
    const auto rr = sediment_preset<float>(sediment::rough_rock);
    CHECK(rr.rho == 2.5f);
    CHECK(rr.nu == 2.5f);
    CHECK(rr.w2_cm4 == 0.20693f);
    const auto cl = sediment_preset<double>(sediment::clay);
    CHECK(cl.nu == 0.98);
    CHECK(cl.delta == 0.00148);
    CHECK(cl.sigma2 == 0.001);
    CHECK(sediment_table.size() == 15);
    for (std::size_t i = 0; i < sediment_table.size(); ++i) {
        CAPTURE(sediment_table[i].name);
        CHECK(static_cast<std::size_t>(sediment_table[i].id) == i);
        CHECK(sediment_preset<double>(sediment_table[i].id).gamma == 3.25);
        CHECK_NOTHROW(validate(sediment_preset<double>(sediment_table[i].id), "preset"));
        CHECK_NOTHROW(validate(sediment_preset<float>(sediment_table[i].id), "preset"));
    }
}

TEST_CASE("sediment presets are found by name, alias, any case and separator") {
    CHECK(sediment_from_name("medium_sand") == sediment::medium_sand);
    CHECK(sediment_from_name("Medium Sand") == sediment::medium_sand);
    CHECK(sediment_from_name("very-fine-sand") == sediment::very_fine_sand);
    CHECK(sediment_from_name("gravel") == sediment::cobble);
    CHECK(sediment_from_name("silty sand") == sediment::fine_sand);
    CHECK(sediment_from_name("SILT") == sediment::sandy_mud);
    CHECK(sediment_preset<double>("rock").w2_cm4 == 0.01862);
    for (const auto& row : sediment_table) CHECK(sediment_from_name(row.name) == row.id);
}

TEST_CASE("an unknown sediment name is rejected, naming it and listing the valid names") {
    try {
        (void)sediment_preset<float>("quicksand");
        FAIL("no exception");
    } catch (const sss::invalid_parameter& e) {
        const std::string what = e.what();
        CHECK(e.parameter() == "sediment");
        CHECK(what.find("quicksand") != std::string::npos);
        CHECK(what.find("medium_sand") != std::string::npos);
        CHECK(what.find("rough_rock") != std::string::npos);
        CHECK(what.find("clay") != std::string::npos);
    }
}

TEST_CASE("the grain-size regressions reproduce TR 9407 Table 2 within its printed precision") {
    for (const printed_row& r : table2) {
        CAPTURE(r.mz_phi);
        const auto p = sediment_from_grain_size(r.mz_phi);
        CHECK(std::abs(p.rho - r.rho) <= half_unit_of_print(r.rho_dec));
        CHECK(std::abs(p.nu - r.nu) <= half_unit_of_print(r.nu_dec));
        CHECK(std::abs(p.delta - r.delta) <= half_unit_of_print(r.delta_dec));
        CHECK(p.sigma2 == r.sigma2);
        CHECK(std::abs(p.w2_cm4 - r.w2) <= half_unit_of_print(r.w2_dec));
        CHECK(p.gamma == 3.25);
        // The presets at these grain sizes are the printed rows themselves.
        CHECK(sediment_preset<double>(r.id).rho == r.rho);
        CHECK(sediment_table[static_cast<std::size_t>(r.id)].mz_phi == r.mz_phi);
    }
}

TEST_CASE("the grain-size regressions accept -1 to 9 phi, ends included, and nothing else") {
    CHECK_NOTHROW((void)sediment_from_grain_size(-1.0));
    CHECK_NOTHROW((void)sediment_from_grain_size(9.0f));
    for (double bad : {-1.01, 9.01, -5.0, 20.0, std::nan("")}) {
        CAPTURE(bad);
        try {
            (void)sediment_from_grain_size(bad);
            FAIL("no exception");
        } catch (const sss::invalid_parameter& e) {
            CHECK(e.parameter() == "mz_phi");
        }
    }
    // Everywhere inside the range the parameters are valid model inputs.
    for (double mz = -1.0; mz <= 9.0; mz += 0.05) {
        CAPTURE(mz);
        CHECK_NOTHROW(validate(sediment_from_grain_size(mz), "regression"));
    }
}

TEST_CASE("sediment validation names the offending parameter") {
    const auto good = sediment_preset<double>(sediment::medium_sand);
    auto expect = [](sediment_params<double> p, const char* name) {
        CAPTURE(name);
        try {
            validate(p, "bed");
            FAIL("no exception");
        } catch (const sss::invalid_parameter& e) {
            CHECK(e.parameter() == name);
        }
    };
    auto p = good;
    p.rho = 0.0;
    expect(p, "bed.rho");
    p = good;
    p.nu = -1.0;
    expect(p, "bed.nu");
    p = good;
    p.delta = 0.0;
    expect(p, "bed.delta");
    p = good;
    p.sigma2 = -1e-3;
    expect(p, "bed.sigma2");
    p = good;
    p.gamma = 4.0;
    expect(p, "bed.gamma");
    p = good;
    p.gamma = 2.0;
    expect(p, "bed.gamma");
    p = good;
    p.w2_cm4 = std::nan("");
    expect(p, "bed.w2_cm4");
    p = good;
    p.sigma2 = 0.0; // volume scattering off is allowed
    CHECK_NOTHROW(validate(p, "bed"));
}
