// Numbers that every program uses.

const INFINITY: f32 = 3.402823466e38;
const PI: f32 = 3.14159265358979;
