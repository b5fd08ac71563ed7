#pragma once
// What every part of the Python module shares: the exceptions, JSON documents as Python
// objects, numpy arrays from vectors, the thread count of a run, the lab readers' warnings as
// Python warnings, and how a run that releases the GIL still stops on Ctrl-C.
//
// Interrupts. A run releases the GIL; Python's SIGINT handler then only marks the signal, and
// the KeyboardInterrupt is raised by whoever next runs PyErr_CheckSignals() on the main thread.
//   - a run on the calling thread (a cube test) checks from the test loop's progress hook, at
//     most every kSignalCheckSeconds: SignalCheck takes the GIL there and throws Interrupted,
//     which unwinds the test (the World and every buffer are RAII) to the binding, which raises
//     the pending Python error;
//   - work on other threads (a calibration's worker threads) runs in_background(): the calling
//     thread waits for it and checks the signals meanwhile; on an interrupt it raises the
//     cancel flag, which the work's own hooks (after each run) turn into Interrupted, waits
//     for the work to end (runs in flight finish and are recorded), then raises.
// A Python callback given to a run (progress=...) that raises stops the run the same way, with
// the callback's exception.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <exception>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace gradem::py_api {

namespace py = pybind11;

/// Thrown inside a run whose Python error (KeyboardInterrupt, a callback's exception) is
/// pending: the binding raises that error once the run has unwound.
struct Interrupted : std::exception {
    [[nodiscard]] const char* what() const noexcept override { return "interrupted"; }
};

inline constexpr double kSignalCheckSeconds = 0.1;

/// Called from the thread a run runs on (GIL released): every kSignalCheckSeconds, takes the
/// GIL and runs Python's signal handlers; throws Interrupted when one raised.
class SignalCheck {
public:
    void operator()();

private:
    std::chrono::steady_clock::time_point next_ = std::chrono::steady_clock::now();
};

/// Calls a Python callable with the GIL taken; its exception becomes the pending error and
/// Interrupted is thrown.
void call_python(const py::object& callable, const std::function<py::object()>& make_argument);

/// Runs `work` on a thread of its own while this thread (holding the GIL on entry) waits with
/// the GIL released and checks for signals; on an interrupt `cancel` is set and the work is
/// waited for. Exceptions of the work are rethrown here; Interrupted raises the pending error.
void in_background(const std::function<void()>& work, std::atomic<bool>& cancel);

/// Sets the OpenMP thread count of the calling thread for a run (nullopt: leave it) and
/// restores it afterwards. A count below 1 is a ValueError.
class RunThreads {
public:
    explicit RunThreads(std::optional<int> threads);
    ~RunThreads();
    RunThreads(const RunThreads&) = delete;
    RunThreads& operator=(const RunThreads&) = delete;
    [[nodiscard]] int threads() const { return threads_; }

private:
    int saved_ = 1, threads_ = 1;
};

/// Collects the lab readers' warnings (rows skipped, nominal dimensions) during a call; emit()
/// (GIL held) issues each as a Python warning of class gradem.LabWarning.
class LabWarnings {
public:
    LabWarnings();
    ~LabWarnings();
    void emit();

private:
    std::vector<std::string> lines_;
};

/// A JSON text as Python objects (json.loads: dicts keep the document's key order).
py::object json_to_python(const std::string& text);
inline py::object json_to_python(const nlohmann::json& j) { return json_to_python(j.dump()); }
inline py::object json_to_python(const nlohmann::ordered_json& j) { return json_to_python(j.dump()); }

template <typename T>
py::array_t<T> to_array(const std::vector<T>& v) {
    py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

/// A column of `rows` through `get`, as a numpy array.
template <typename T, typename Row, typename Get>
py::array_t<T> column(const std::vector<Row>& rows, Get get) {
    py::array_t<T> a(static_cast<py::ssize_t>(rows.size()));
    T* out = a.mutable_data();
    for (std::size_t k = 0; k < rows.size(); ++k) out[k] = static_cast<T>(get(rows[k]));
    return a;
}

/// The exception classes (gradem.InputError: ValueError; gradem.RunError: RuntimeError).
py::object input_error_class();
py::object run_error_class();

/// The parts of the module, each in its own file.
void register_errors(py::module_& m);
void register_config(py::module_& m);
void register_virtual_tests(py::module_& m);
void register_calibration(py::module_& m);
void register_model(py::module_& m);
void register_lab(py::module_& m);

}  // namespace gradem::py_api
