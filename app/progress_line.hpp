#pragma once
// The progress line the long-running test commands (compress, tension) print on stderr while a
// test runs (nothing with --quiet): elapsed time, strain, stress, peak, breaks and an ETA.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>

#include "app/console.hpp"
#include "common/clock_text.hpp"
#include "experiments/virtual_tests/axial_loading.hpp"

namespace gradem::app {

/// One progress line on stderr: rewritten in place on a terminal (every second), a new line
/// every 10 s otherwise. ETA: the end strain is guessed as max(2 x strain at the peak so far,
/// current strain), at most max_strain, and approached at the strain rate measured so far.
class ProgressLine {
    using Clock = std::chrono::steady_clock;

public:
    ProgressLine(std::string label, double max_strain)
        : label_(std::move(label)), max_strain_(max_strain), out_(console().notes()), tty_(isatty(fileno(out_)) != 0),
          start_(Clock::now()), last_(start_) {}

    void update(const exp::CurvePoint& p, double peak) {
        const auto now = Clock::now();
        if (!first_) first_ = {now, p.platen_strain};
        if (p.stress >= peak) peak_strain_ = p.platen_strain;
        if (now - last_ < std::chrono::seconds(tty_ ? 1 : 10)) return;
        last_ = now;
        const double elapsed = seconds(start_, now);
        const double rate = (p.platen_strain - first_->second) / seconds(first_->first, now);  // strain per wall second
        const double end = std::min(max_strain_, std::max(2.0 * peak_strain_, p.platen_strain));
        const double eta = rate > 0.0 ? (end - p.platen_strain) / rate : std::nan("");
        std::fprintf(out_, "%s%s: %s  strain %.5f  stress %.3f MPa  peak %.3f MPa  breaks %lld  ETA %s%s",
                     tty_ ? "\r" : "", label_.c_str(), common::clock_text(elapsed).c_str(), p.platen_strain,
                     p.stress * 1e-6, peak * 1e-6, static_cast<long long>(p.broken_tension + p.broken_shear),
                     common::clock_text(eta).c_str(), tty_ ? "   " : "\n");
        printed_ = true;
    }

    void finish() const {
        if (tty_ && printed_) std::fprintf(out_, "\n");
    }

    exp::ProgressCallback callback() {
        return [this](const exp::CurvePoint& p, double peak) { update(p, peak); };
    }

private:
    static double seconds(Clock::time_point a, Clock::time_point b) {
        return std::chrono::duration<double>(b - a).count();
    }

    std::string label_;
    double max_strain_;
    std::FILE* out_;
    bool tty_;
    Clock::time_point start_, last_;
    std::optional<std::pair<Clock::time_point, double>> first_;  // first point: time, strain
    double peak_strain_ = 0.0;
    bool printed_ = false;
};

}  // namespace gradem::app
