// The contract is in src/b.h; the algorithm in src/missing.h (a dead reference).
const char* kUrl = "http://example.com/src/not-a-comment.h";
