// Closes what methods/shared_source_begin.h opened.
#undef precise
#undef RT_ON_INNER
#undef RT_ON_OUTER
#undef RT_INOUT
#undef RT_OUT
#pragma GCC diagnostic pop
