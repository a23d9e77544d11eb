//! Fixed-point formats, angles, trig, reciprocals and exact integer geometry.
