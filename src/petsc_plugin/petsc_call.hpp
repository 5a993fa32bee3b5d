#pragma once
// PETSc reports errors as return codes; the plugin turns them into exceptions that carry PETSc's
// own message, and catches them at its interface (which reports failures as strings).
#include <petscsys.h>

#include <stdexcept>
#include <string>

namespace moreau::petsc_plugin {

class PetscFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws PetscFailure naming `what` and PETSc's message if `code` is not 0.
inline void petsc_call(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  char* specific = nullptr;
  PetscErrorMessage(code, &text, &specific);
  std::string message = std::string(what) + ": " + (text ? text : "PETSc error");
  if (specific && *specific) message += " (" + std::string(specific) + ")";
  throw PetscFailure(message);
}

}  // namespace moreau::petsc_plugin
