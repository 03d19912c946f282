#include "mesogen/generate.hpp"
#include <stdexcept>
namespace cdem::mesogen {
void run_generate(const GenerateRequest&) { throw std::logic_error("generate: pipeline not assembled yet"); }
}
