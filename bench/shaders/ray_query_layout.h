// The bindings of the ray-query anchor's kernel (ray_query_trace.comp), for it and for
// bench/ray_query_anchor.cpp, which binds by these names.
#ifndef HMB_BENCH_SHADERS_RAY_QUERY_LAYOUT_H
#define HMB_BENCH_SHADERS_RAY_QUERY_LAYOUT_H

#define HMB_RAY_QUERY_BINDING_SCENE 0  // the top-level acceleration structure
#define HMB_RAY_QUERY_BINDING_RAYS 1   // AnchorRay per ray
#define HMB_RAY_QUERY_BINDING_HITS 2   // AnchorHit per ray
#define HMB_RAY_QUERY_GROUP 64

#endif
