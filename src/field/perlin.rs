//! Periodic multi-octave Perlin noise (fBm), Li Tian eq. 9.
