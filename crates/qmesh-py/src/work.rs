//! Long computations off the Python thread: the work runs on its own thread while the
//! caller waits without the GIL, checking for Ctrl-C every 50 ms. On Ctrl-C the call
//! raises KeyboardInterrupt at once; the abandoned work finishes in the background and
//! its result is dropped.

use std::sync::Mutex;
use std::sync::mpsc::{RecvTimeoutError, channel};
use std::time::Duration;

use pyo3::prelude::*;

use crate::errors::value_error;

pub fn interruptible<T: Send + 'static>(py: Python<'_>, work: impl FnOnce() -> T + Send + 'static) -> PyResult<T> {
    let (tx, rx) = channel();
    let rx = Mutex::new(rx); // (a Receiver is not Sync; the detached closure borrows it)
    std::thread::spawn(move || {
        let _ = tx.send(work());
    });
    loop {
        match py.detach(|| rx.lock().expect("only this thread locks it").recv_timeout(Duration::from_millis(50))) {
            Ok(value) => return Ok(value),
            Err(RecvTimeoutError::Timeout) => py.check_signals()?,
            Err(RecvTimeoutError::Disconnected) => {
                return Err(value_error(
                    py,
                    "internal error: the computation stopped (a qmesh defect; please report it)",
                ));
            }
        }
    }
}
