//! Build-time generation of the engine's numeric tables (trig, reciprocals).
