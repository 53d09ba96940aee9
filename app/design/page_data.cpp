// The page (HTML with the WebAssembly module inlined) is linked into the binary as it was built,
// so `chutelab design` works from build/app/chutelab or an installed copy alike, with no file to
// find at run time.
#include "app/design/page.h"

#if defined(CHUTELAB_DESIGN_PAGE_FILE)
__asm__(".section .rodata\n"
        ".balign 16\n"
        ".global chutelab_design_page_begin\n"
        ".hidden chutelab_design_page_begin\n"
        "chutelab_design_page_begin:\n"
        ".incbin \"" CHUTELAB_DESIGN_PAGE_FILE "\"\n"
        ".global chutelab_design_page_end\n"
        ".hidden chutelab_design_page_end\n"
        "chutelab_design_page_end:\n"
        ".byte 0\n"
        ".previous\n");
extern "C" const char chutelab_design_page_begin[];
extern "C" const char chutelab_design_page_end[];

std::optional<std::string_view> chutelab::app::design_page() {
  return std::string_view(chutelab_design_page_begin,
                          static_cast<std::size_t>(chutelab_design_page_end - chutelab_design_page_begin));
}
#else
std::optional<std::string_view> chutelab::app::design_page() { return std::nullopt; }
#endif
