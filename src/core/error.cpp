#include <radiosity/error.h>
#include <radiosity/message_text.h>

namespace rad {

InputError::InputError(const std::string& where, const std::string& what)
    : std::runtime_error(printableMessage(where.empty() ? what : where + ": " + what)) {}

InputError::InputError(const std::string& message)
    : std::runtime_error(printableMessage(message)) {}

}  // namespace rad
