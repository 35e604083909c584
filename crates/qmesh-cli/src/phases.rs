//! Seconds per phase of a command, for `--json` (`"phases": {"read": …, …}`): a clock
//! that each phase ends with [`Phases::lap`], and the lookup and application times a
//! query-replace reports.

use std::time::Instant;

use qmesh::replace::ReplaceReport;

/// The phases so far, in order.
pub struct Phases {
    last: Instant,
    list: Vec<(&'static str, f64)>,
}

impl Phases {
    pub fn start() -> Self {
        Phases { last: Instant::now(), list: Vec::new() }
    }

    /// Ends phase `name` now.
    pub fn lap(&mut self, name: &'static str) {
        let now = Instant::now();
        self.list.push((name, (now - self.last).as_secs_f64()));
        self.last = now;
    }

    /// Ends a query-replace phase: its edge splits, lookups and replacements as three
    /// phases, the rest of the time since the last lap as `name`.
    pub fn lap_replace(&mut self, name: &'static str, r: &ReplaceReport) {
        let inner = [
            ("split_edges", r.split_seconds),
            ("lookup", r.query_seconds),
            ("apply", r.replace_seconds - r.split_seconds),
        ];
        self.lap_inner(name, &inner);
    }

    /// Ends a phase made of `inner` phases (a library call's own): those, and the
    /// rest of the time since the last lap as `name`.
    pub fn lap_inner(&mut self, name: &'static str, inner: &[(&'static str, f64)]) {
        let now = Instant::now();
        let whole = (now - self.last).as_secs_f64();
        self.list.extend_from_slice(inner);
        self.list.push((name, (whole - inner.iter().map(|p| p.1).sum::<f64>()).max(0.0)));
        self.last = now;
    }

    /// The phases as a JSON object (and their sum as `total`).
    pub fn json(&self) -> serde_json::Value {
        let mut m: serde_json::Map<String, serde_json::Value> =
            self.list.iter().map(|&(n, s)| (n.to_string(), s.into())).collect();
        m.insert("total".into(), self.list.iter().map(|p| p.1).sum::<f64>().into());
        serde_json::Value::Object(m)
    }
}
