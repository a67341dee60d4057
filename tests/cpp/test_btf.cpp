// BTF subsystem: file-name parsing, the shared-design linear fit against an analytic Lambertian
// BTF, the n_s = (0,0,1) specular variant, the built-in LM, and IO round trips and errors.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>

#include <gtest/gtest.h>

#include <weft/BtfIo.h>
#include <weft/BtfNonlinear.h>
#include <weft/BtfSynth.h>
#include <weft/Error.h>

#include "TempDir.h"
#include "btf/BlinnPhongTexel.h"
#include "btf/BtfShadowClassify.h"
#include "btf/Cholesky3.h"

namespace {

std::vector<weft::BtfAngles> frontal() {
    std::vector<weft::BtfAngles> out;
    for (const glm::vec2& d : weft::btfStandardDirections()) out.push_back({d.x, d.y, 0, 0});
    return out;
}

// A small material with tilted normals (at most ~14°), no specular.
weft::BtfMaterialMaps lambertian(int w, int h) {
    weft::BtfMaterialMaps m;
    m.width = w;
    m.height = h;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const glm::vec3 n = glm::normalize(
                glm::vec3(0.2f * std::sin(float(x)), 0.15f * std::cos(float(y)), 1.0f));
            for (int k = 0; k < 3; ++k) {
                m.normal.push_back(n[k]);
                m.albedo.push_back(0.3f + 0.1f * float(k) + 0.01f * float(x));
                m.ambient.push_back(0.1f + 0.02f * float(y));
            }
        }
    return m;
}

TEST(Btf, ParsesFileNamesByKey) {
    weft::BtfAngles a;
    ASSERT_TRUE(weft::parseBtfFileName("dir/00084 tl015 pl000 tv015 pv120.jpg", a));
    EXPECT_EQ(a.thetaLight, 15);
    EXPECT_EQ(a.phiView, 120);
    ASSERT_TRUE(weft::parseBtfFileName("Wool_00084_pv120_tv015_pl300_tl075.png", a));
    EXPECT_EQ(a.thetaLight, 75);
    EXPECT_EQ(a.phiLight, 300);
    EXPECT_FALSE(weft::parseBtfFileName("00084 tl015 pl000 tv015.jpg", a));
    EXPECT_EQ(weft::btfStandardDirections().size(), 81u);
}

TEST(Btf, CholeskyRejectsSingularMatrices) {
    const double singular[3][3] = {{1, 2, 3}, {2, 4, 6}, {3, 6, 9}};
    weft::Cholesky3 f;
    EXPECT_FALSE(f.factor(singular, 1e-12));
    const double spd[3][3] = {{4, 1, 0}, {1, 3, 1}, {0, 1, 2}};
    ASSERT_TRUE(f.factor(spd, 1e-12));
    const double b[3] = {1, 2, 3};
    double x[3];
    f.solve(b, x);
    for (int i = 0; i < 3; ++i)
        EXPECT_NEAR(spd[i][0] * x[0] + spd[i][1] * x[1] + spd[i][2] * x[2], b[i], 1e-12);
}

// The shadow classification's σ takes the median of the steep residuals by rank where there are
// up to 32: the element nth_element picks, also with ties, left-out samples and fewer than 5
// steep ones (all used samples then).
TEST(Btf, SteepResidualMedianIsTheOrderStatistic) {
    std::mt19937 rng(7);
    for (int trial = 0; trial < 2000; ++trial) {
        const size_t count = 1 + rng() % 90;
        std::vector<double> lit(count), seen(count);
        std::vector<float> lz(count), used(count);
        for (size_t s = 0; s < count; ++s) {
            lit[s] = double(rng() % 7) * 0.25; // few distinct values: many equal residuals
            seen[s] = trial % 2 ? double(rng() % 9) * 0.125 : double(rng()) / rng.max();
            lz[s] = float(rng() % 100) / 100.0f;
            used[s] = rng() % 5 ? 1.0f : 0.0f;
        }
        std::vector<double> res;
        for (size_t s = 0; s < count; ++s)
            if (used[s] > 0.0f && lz[s] >= 0.85f) res.push_back(std::fabs(seen[s] - lit[s]));
        if (res.size() < 5)
            for (size_t s = 0; s < count; ++s)
                if (used[s] > 0.0f) res.push_back(std::fabs(seen[s] - lit[s]));
        double expected = 0.0;
        if (!res.empty()) {
            std::nth_element(res.begin(), res.begin() + long(res.size() / 2), res.end());
            expected = res[res.size() / 2] / 0.6745;
        }
        EXPECT_EQ(weft::steepResidualSigma(count, lit.data(), seen.data(), lz.data(), used.data()),
                  expected)
            << "trial " << trial << ", " << count << " samples";
    }
}

// blinnPhongTerms keeps the last θ's terms: asked again at the same θ for another geometry it
// computes that geometry's, d = max(n·l, 0) for its lights.
TEST(Btf, ModelTermsFollowTheGeometryAtOneTheta) {
    const std::vector<glm::vec3> a = {glm::normalize(glm::vec3(0.3f, 0.1f, 1.0f)),
                                      glm::normalize(glm::vec3(-0.5f, 0.2f, 0.8f))};
    const std::vector<glm::vec3> b = {glm::normalize(glm::vec3(0.9f, -0.4f, 0.2f)),
                                      glm::normalize(glm::vec3(0.0f, 0.6f, 0.7f))};
    auto halves = [](const std::vector<glm::vec3>& l) {
        std::vector<glm::vec3> h;
        for (const glm::vec3& d : l) h.push_back(glm::normalize(d + glm::vec3(0, 0, 1)));
        return h;
    };
    const weft::BlinnPhongGeometry ga(a, halves(a)), gb(b, halves(b));
    std::vector<float> planes(3 * size_t(ga.padded), 0.5f);
    weft::BlinnPhongTexel tx;
    const double theta[3] = {0.1, -0.2, std::log(20.0)};
    const glm::dvec3 n = tx.normal(theta[0], theta[1]);
    std::vector<double> d, g;
    for (const weft::BlinnPhongGeometry* geo : {&ga, &gb, &ga}) {
        tx.geometry = geo;
        tx.setPlanes(planes.data());
        weft::blinnPhongTerms(tx, theta, d, g);
        const std::vector<glm::vec3>& lights = geo == &ga ? a : b;
        ASSERT_EQ(d.size(), lights.size());
        for (size_t s = 0; s < lights.size(); ++s)
            EXPECT_NEAR(d[s], std::max(glm::dot(n, glm::dvec3(lights[s])), 0.0), 1e-6);
    }
}

TEST(Btf, LinearFitRecoversLambertianNormals) {
    const weft::BtfMaterialMaps truth = lambertian(7, 5);
    const weft::BtfSamples samples = weft::renderBtf(truth, frontal());
    const weft::BtfLinearFit fit = weft::fitBtfLinear(samples);
    const weft::BtfMaterialMaps maps = weft::btfMaterialFromLinear(fit);
    for (size_t i = 0; i < maps.normal.size(); i += 3) {
        const glm::vec3 a(maps.normal[i], maps.normal[i + 1], maps.normal[i + 2]);
        const glm::vec3 b(truth.normal[i], truth.normal[i + 1], truth.normal[i + 2]);
        const float degrees = std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 57.3f;
        EXPECT_LT(degrees, 0.01f);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(maps.ambient[i + k], truth.ambient[i + k], 1e-5f);
    }
    EXPECT_EQ(fit.darkTexels, 0);
}

TEST(Btf, FlatSpecularNormalReproducesTheFrontalSample) {
    weft::BtfMaterialMaps truth = lambertian(6, 6);
    truth.specular.assign(truth.albedo.size(), 0.1f);
    truth.exponent = 40;
    const weft::BtfSamples samples = weft::renderBtf(truth, frontal());
    const weft::BtfSpecularFit spec =
        weft::fitBtfSpecular(samples, weft::fitBtfLinear(samples), {});
    const std::vector<double> errors = weft::btfSampleErrors(samples, spec.maps);
    EXPECT_EQ(spec.specularSample, 0);
    EXPECT_LT(errors[0], 1e-12);
    EXPECT_GT(spec.maps.exponent, 1.0f);
}

TEST(Btf, BuiltinLevenbergMarquardtFitsBlinnPhong) {
    weft::BtfMaterialMaps truth = lambertian(4, 4);
    truth.specular.assign(truth.albedo.size(), 0.2f);
    truth.exponent = 60;
    truth.clampDiffuse = true;
    const weft::BtfSamples samples = weft::renderBtf(truth, frontal());
    const weft::BtfSpecularFit seed =
        weft::fitBtfSpecular(samples, weft::fitBtfLinear(samples), {});
    weft::BtfNonlinearOptions options;
    options.solver = weft::BtfSolver::Builtin;
    options.maxIterations = 80;
    const weft::BtfNonlinearFit fit = weft::fitBtfBlinnPhong(samples, seed.maps, options);
    EXPECT_EQ(fit.solver, "builtin");
    for (float e : fit.maps.exponentMap) EXPECT_NEAR(e, 60.0f, 0.05f);
    double total = 0;
    for (double e : weft::btfSampleErrors(samples, fit.maps)) total += e;
    EXPECT_LT(total, 1e-10);
}

TEST(Btf, WritesAndReadsTheBonnLayout) {
    TempDir dir;
    const weft::BtfSamples samples = weft::renderBtf(lambertian(5, 4), frontal());
    weft::BtfWriteOptions o;
    o.format = weft::BtfImageFormat::Png;
    o.zip = true;
    weft::writeBtf(dir.file("b.zip"), samples, o);
    const weft::BtfSamples back = weft::loadBtf(dir.file("b.zip"));
    ASSERT_EQ(back.count(), 81);
    ASSERT_EQ(back.width(), 5);
    for (size_t i = 0; i < back.values().size(); ++i)
        EXPECT_NEAR(back.values()[i], samples.values()[i], 0.5f / 255.0f + 1e-6f);
    EXPECT_THROW(weft::loadBtf(dir.file("none")), weft::IoError);
    dir.write("junk.zip", "PK\x03\x04 not really a zip");
    EXPECT_THROW(weft::loadBtf(dir.file("junk.zip")), weft::IoError);
    weft::BtfLoadOptions bad;
    bad.views = {glm::vec2(120.0f, 0.0f)};
    EXPECT_THROW(weft::loadBtf(dir.file("b.zip"), bad), weft::InvalidArgument);
}

} // namespace
