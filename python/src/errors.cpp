#include "errors.hpp"

#include "bindings.hpp"

namespace py = pybind11;

namespace geotex::python {

namespace {

// The classes live as long as the module, which holds them as attributes; these are borrowed
// references set once at import.
struct Classes {
    py::handle error, usage, input, parse, io, processing, numerical;
};
Classes g_classes;

py::handle make_class(py::module_& m, const char* name, const char* doc, py::tuple bases) {
    const std::string qualified = std::string("geotex.") + name;
    PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
    if (cls == nullptr) throw py::error_already_set();
    m.add_object(name, py::reinterpret_steal<py::object>(cls));
    return cls;
}

[[noreturn]] void raise(py::handle cls, const std::string& message, const std::string& file,
                        long line, long column) {
    py::object exc = cls(message);
    exc.attr("file") = file.empty() ? py::object(py::none()) : py::object(py::str(file));
    exc.attr("line") = line;
    exc.attr("column") = column;
    PyErr_SetObject(cls.ptr(), exc.ptr());
    throw py::error_already_set();
}

py::handle class_of(Phase phase, const Error& error) {
    switch (phase) {
        case Phase::Usage:
            return g_classes.usage;
        case Phase::Input:
            if (dynamic_cast<const ParseError*>(&error) != nullptr) return g_classes.parse;
            if (dynamic_cast<const IoError*>(&error) != nullptr) return g_classes.io;
            return g_classes.input;
        case Phase::Processing:
            if (dynamic_cast<const NumericalError*>(&error) != nullptr) return g_classes.numerical;
            return g_classes.processing;
    }
    return g_classes.error;
}

py::handle class_of(Phase phase) {
    switch (phase) {
        case Phase::Usage:
            return g_classes.usage;
        case Phase::Input:
            return g_classes.input;
        case Phase::Processing:
            return g_classes.processing;
    }
    return g_classes.error;
}

}  // namespace

void raise_error(Phase phase, const Error& error, const std::string& file) {
    raise(class_of(phase, error), error.located(file), error.file().empty() ? file : error.file(),
          error.line(), error.column());
}

void raise_error(Phase phase, const std::string& message) {
    raise(class_of(phase), message, {}, 0, 0);
}

void bind_errors(py::module_& m) {
    Classes& c = g_classes;
    c.error = make_class(m, "Error",
                         "Base of geotex's errors. str() is the message as the command prints it; "
                         "file, line and column locate it when known (None, 0, 0 otherwise).",
                         py::make_tuple(py::handle(PyExc_Exception)));
    // Defaults, so that an instance raised from Python code has them too.
    c.error.attr("file") = py::none();
    c.error.attr("line") = 0;
    c.error.attr("column") = 0;
    c.usage = make_class(m, "UsageError",
                         "A keyword argument the command would refuse as an option (exit code 1).",
                         py::make_tuple(c.error, py::handle(PyExc_ValueError)));
    c.input =
        make_class(m, "InputError",
                   "The input mesh, a file or arrays, is unusable (the command's exit code 2).",
                   py::make_tuple(c.error));
    c.parse = make_class(m, "ParseError", "A mesh file whose content does not follow its format.",
                         py::make_tuple(c.input));
    c.io = make_class(m, "IoError", "A file that cannot be opened or read.",
                      py::make_tuple(c.input, py::handle(PyExc_OSError)));
    c.processing = make_class(m, "ProcessingError",
                              "The pipeline failed on valid input (the command's exit code 3).",
                              py::make_tuple(c.error));
    c.numerical = make_class(m, "NumericalError", "A computation that failed numerically.",
                             py::make_tuple(c.processing));
}

}  // namespace geotex::python
