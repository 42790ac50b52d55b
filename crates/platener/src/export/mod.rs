//! Step `export`: SVG and DXF per sheet, PNG previews, report.json and the ZIP.
