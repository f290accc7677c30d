//! The package's exceptions. Their messages are the one-line messages the command line prints.

use hatchery_nodes::SessionError;
use pyo3::PyErr;
use pyo3::create_exception;
use pyo3::exceptions::PyException;

create_exception!(
    _hatchery,
    HatcheryError,
    PyException,
    "Base of every error hatchery raises."
);
create_exception!(
    _hatchery,
    GraphError,
    HatcheryError,
    "A graph that cannot be read or is invalid (syntax, unknown kind, type-mismatched edge, \
     cycle), or an unknown node or port."
);
create_exception!(
    _hatchery,
    InputError,
    HatcheryError,
    "A graph input that cannot take what was given: no such input, a file or array of the wrong \
     kind, an unreadable file, an array of the wrong shape or type, or a node that failed on it."
);
create_exception!(
    _hatchery,
    ParamError,
    HatcheryError,
    "A parameter that does not exist or cannot take the value given."
);
create_exception!(
    _hatchery,
    RenderError,
    HatcheryError,
    "A node that failed while rendering, or a GPU that cannot be opened."
);

create_exception!(
    _hatchery,
    JobError,
    HatcheryError,
    "A batch job file that cannot be read or expanded, or a batch run that cannot start."
);

/// A session error as the exception of what failed, chosen by the error's type: an invalid graph
/// or an unknown node or port as GraphError, a graph input that cannot take what was given as
/// InputError, a parameter value as ParamError, the rest (a node that failed, the GPU, a file
/// that cannot be written) as RenderError.
pub fn render_error(e: SessionError) -> PyErr {
    let message = e.to_string();
    match e {
        SessionError::Graph(_) | SessionError::NotFound(_) => GraphError::new_err(message),
        SessionError::Input(_) => InputError::new_err(message),
        SessionError::Param { .. } => ParamError::new_err(message),
        _ => RenderError::new_err(message),
    }
}
