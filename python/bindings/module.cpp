// The extension module gradem._gradem: the shared machinery of common.hpp and the exceptions;
// each part registers its functions (config.cpp, virtual_tests.cpp, calibration.cpp, model.cpp,
// lab.cpp).
// The Python package python/gradem/ wraps it.
#include <pybind11/pybind11.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <future>
#include <memory>
#include <stdexcept>
#include <thread>

#include "calibrate/evaluator.hpp"
#include "calibrate/execution/code_version.hpp"
#include "calibrate/execution/ledger.hpp"
#include "common/input_error.hpp"
#include "experiments/specimen/genesis.hpp"
#include "lab_data/lab_warning.hpp"
#include "python/bindings/common.hpp"

namespace gradem::py_api {

namespace {

// A Python error taken out of the interpreter (PyErr_Fetch) until the binding raises it again.
// Never released without the GIL: when it is not raised (cannot happen: every Interrupted
// reaches the translator), its references are leaked rather than released unsafely.
struct PendingError {
    PyObject *type = nullptr, *value = nullptr, *traceback = nullptr;
    static std::shared_ptr<PendingError> fetch() {  // GIL held
        auto e = std::make_shared<PendingError>();
        PyErr_Fetch(&e->type, &e->value, &e->traceback);
        return e;
    }
    void restore() {  // GIL held
        if (type) PyErr_Restore(type, value, traceback);
        else PyErr_SetNone(PyExc_KeyboardInterrupt);
        type = value = traceback = nullptr;
    }
};

// Interrupted with the error to raise (none: the work was cancelled by the calling thread).
struct InterruptedWith : Interrupted {
    explicit InterruptedWith(std::shared_ptr<PendingError> e) : error(std::move(e)) {}
    std::shared_ptr<PendingError> error;
};

py::object g_input_error, g_run_error, g_lab_warning;

}  // namespace

py::object input_error_class() { return g_input_error; }
py::object run_error_class() { return g_run_error; }

void SignalCheck::operator()() {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_) return;
    next_ = now + std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(kSignalCheckSeconds));
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw InterruptedWith(PendingError::fetch());
}

void call_python(const py::object& callable, const std::function<py::object()>& make_argument) {
    py::gil_scoped_acquire gil;
    try {
        callable(make_argument());
    } catch (py::error_already_set& e) {
        e.restore();
        throw InterruptedWith(PendingError::fetch());
    }
}

void in_background(const std::function<void()>& work, std::atomic<bool>& cancel) {
    std::shared_ptr<PendingError> interrupt;  // the calling thread's KeyboardInterrupt
    std::exception_ptr failure;
    {
        py::gil_scoped_release release;
        std::promise<void> done;
        std::future<void> finished = done.get_future();
        std::thread worker([&] {
            try {
                work();
                done.set_value();
            } catch (...) {
                done.set_exception(std::current_exception());
            }
        });
        while (finished.wait_for(std::chrono::duration<double>(kSignalCheckSeconds)) != std::future_status::ready) {
            if (interrupt) continue;
            py::gil_scoped_acquire gil;
            if (PyErr_CheckSignals() != 0) {
                interrupt = PendingError::fetch();
                cancel = true;
            }
        }
        worker.join();
        try {
            finished.get();
        } catch (...) {
            failure = std::current_exception();
        }
    }
    if (interrupt) throw InterruptedWith(interrupt);
    if (failure) std::rethrow_exception(failure);
}

RunThreads::RunThreads(std::optional<int> threads) {
    if (threads && *threads < 1) throw py::value_error("threads = " + std::to_string(*threads) + ": expected an integer >= 1");
#ifdef _OPENMP
    saved_ = omp_get_max_threads();
    if (threads) omp_set_num_threads(*threads);
    threads_ = omp_get_max_threads();
#else
    threads_ = 1;
#endif
}

RunThreads::~RunThreads() {
#ifdef _OPENMP
    omp_set_num_threads(saved_);
#endif
}

LabWarnings::LabWarnings() {
    lab::warning_sink().start([this](const lab::LabWarning& w) { lines_.push_back(w.line()); });
}

LabWarnings::~LabWarnings() { lab::warning_sink().start({}); }

void LabWarnings::emit() {
    const py::object warn = py::module_::import("warnings").attr("warn");
    for (const std::string& line : lines_) {
        const std::string text = line.rfind("warning: ", 0) == 0 ? line.substr(9) : line;
        warn(text, g_lab_warning, 2);
    }
    lines_.clear();
}

py::object json_to_python(const std::string& text) { return py::module_::import("json").attr("loads")(py::str(text)); }

void register_errors(py::module_& m) {
    g_input_error = py::reinterpret_steal<py::object>(
        PyErr_NewExceptionWithDoc("gradem.InputError",
                                  "Bad input: a file, a config key, an override or an argument. The message names "
                                  "the file, line and key as the command line does.",
                                  PyExc_ValueError, nullptr));
    g_run_error = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
        "gradem.RunError", "A run that could not be done (genesis that did not converge, a ledger that cannot be written).",
        PyExc_RuntimeError, nullptr));
    g_lab_warning = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
        "gradem.LabWarning", "What a lab reader did to a file: rows skipped, specimen dimensions taken from nominal values.",
        PyExc_UserWarning, nullptr));
    m.attr("InputError") = g_input_error;
    m.attr("RunError") = g_run_error;
    m.attr("LabWarning") = g_lab_warning;
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const InterruptedWith& e) {
            e.error->restore();
        } catch (const Interrupted&) {
            PyErr_SetNone(PyExc_KeyboardInterrupt);
        } catch (const common::InputError& e) {
            PyErr_SetString(g_input_error.ptr(), e.what());
        } catch (const cal::LedgerMismatch& e) {
            PyErr_SetString(g_input_error.ptr(), e.what());
        } catch (const cal::LedgerError& e) {
            PyErr_SetString(g_run_error.ptr(), e.what());
        } catch (const exp::GenesisError& e) {
            PyErr_SetString(g_run_error.ptr(), e.what());
        } catch (const cal::BudgetExhausted& e) {
            PyErr_SetString(g_run_error.ptr(), e.what());
        }
    });
}

}  // namespace gradem::py_api

PYBIND11_MODULE(_gradem, m) {
    namespace api = gradem::py_api;
    m.doc() = "gradem's C++ core (the package gradem wraps it: python/README.md)";
    m.attr("__version__") = GRADEM_VERSION;
    m.attr("code_version") = gradem::cal::code_version();
    api::register_errors(m);
    api::register_config(m);
    api::register_virtual_tests(m);
    api::register_calibration(m);
    api::register_model(m);
    api::register_lab(m);
}
