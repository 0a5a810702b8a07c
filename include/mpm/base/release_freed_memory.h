#ifndef mpm_base_release_freed_memory_h
#define mpm_base_release_freed_memory_h

#if defined(__GLIBC__)
#  include <malloc.h>
#endif

namespace mpm
{
  /**
   * Hand the memory freed inside the heap back to the operating system.
   * glibc keeps freed blocks of up to 32 MB for reuse, and once the point
   * store has been copied (its layout in cell order), that is the size of
   * the store: without this a run keeps the copy's memory for good. A
   * no-op where the C library is not glibc.
   */
  inline void
  release_freed_memory()
  {
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
  }
} // namespace mpm

#endif
