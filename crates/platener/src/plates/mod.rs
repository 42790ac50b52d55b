//! Step `plates`: inherent and extruded plates with a coverage report.
