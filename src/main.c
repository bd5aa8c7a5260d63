/* The adhbem executable. */
#include "adhbem.h"

static const char help[] = "adhbem: adhesive normal contact with the boundary element method.\n";

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, help));
  PetscCall(PetscFinalize());
  return 0;
}
