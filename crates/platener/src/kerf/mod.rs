//! Step `kerf`: cut paths offset by half the kerf, and the calibration test strip.
