#pragma once
// What a part of a calibration cost in DEM runs (summary.json "runs" "cost", summary.md): the
// runs made now, with their particle-steps (Σ grains × steps of each run) and worker-seconds
// (Σ wall time of each run, whatever ran beside it), and the runs the ledger served, with the
// particle-steps they took when they first ran (what reusing them saved).
#include "calibrate/cube_model.hpp"

namespace gradem::cal {

struct StageCost {
    int executed = 0;                    ///< runs made now
    int from_ledger = 0;                 ///< runs the ledger served
    double particle_steps = 0.0;         ///< Σ grains × steps of the runs made now [-]
    double worker_seconds = 0.0;         ///< Σ wall time of the runs made now [s]
    double ledger_particle_steps = 0.0;  ///< Σ grains × steps of the served runs, when they ran [-]

    void add_run(const RunOutcome& o) {
        ++executed;
        particle_steps += static_cast<double>(o.particles) * static_cast<double>(o.steps);
        worker_seconds += o.wall_seconds;
    }
    void add_served(const RunOutcome& o) {
        ++from_ledger;
        ledger_particle_steps += static_cast<double>(o.particles) * static_cast<double>(o.steps);
    }
    StageCost& operator+=(const StageCost& o) {
        executed += o.executed;
        from_ledger += o.from_ledger;
        particle_steps += o.particle_steps;
        worker_seconds += o.worker_seconds;
        ledger_particle_steps += o.ledger_particle_steps;
        return *this;
    }
};

}  // namespace gradem::cal
