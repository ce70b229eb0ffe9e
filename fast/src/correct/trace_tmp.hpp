#pragma once
namespace linequad {
inline thread_local unsigned lq_trace = 0;
}
#define LQ_TRACE(b) (::linequad::lq_trace |= (1u << (b)))
