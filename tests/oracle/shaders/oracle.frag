#version 450
// Writes id + 1 so that 0 in the id image means "no triangle".
layout(location = 0) flat in uint id;
layout(location = 0) out uint outId;

void main() { outId = id + 1u; }
