//! Cue strike: tip offset and cue speed to cue-ball speed and spin (TP A.30).
