//! Step `sheets`: nesting parts onto sheets.
