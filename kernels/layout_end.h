// Closes what kernels/layout_begin.h opened.
#ifdef __cplusplus
}  // namespace rtbench::gpu
#endif
#undef RTBENCH_CONST
